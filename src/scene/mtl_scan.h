// The MTL scan: checks the Kd/Ks/Ke/Ns/Tf/Ni/illum values of each MTL text with file:line warnings (tinyobjloader
// silently reads junk as 0 and "Kd 0.5" as (0.5, 0, 0)), skips binary MTL files, and joins the rest into the one stream
// tinyobjloader reads. Internal to src/scene; depends on obj_text.h only, never on tinyobjloader.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace lueur::obj {

/// One MTL text and the name it is reported under.
struct MtlSource {
  std::string label;
  std::string text;
};

/// The illumination model a bad or missing `illum` falls back to: today's BRDF (highlight on).
inline constexpr int kDefaultIllum = 2;
/// The index of refraction of glass whose MTL gives none, or a bad one.
inline constexpr float kDefaultIor = 1.5f;

/// One `newmtl` as tinyobjloader will see it; ordinal k here is the k-th named material it returns.
struct MtlEntry {
  std::string name;
  bool single_value[4] = {false, false, false, false};  ///< Kd, Ks, Ke, Tf given as one grey value
  bool has_ns = false;  ///< an Ns statement was given (tinyobjloader reads a missing one as 1; Lueur takes 0)
  bool has_ni = false;  ///< a usable Ni statement was given (tinyobjloader reads a missing one as 1; glass takes 1.5)
  bool has_tf = false;  ///< a Tf (or Kt) statement was given (tinyobjloader reads a missing one as 0; glass takes 1)
  int illum = kDefaultIllum;  ///< the illumination model, 0-10 (an unknown one warned about and replaced)
};

/// The MTL files of a scene as tinyobjloader reads them: one text, and its materials in order.
struct MtlStream {
  std::vector<MtlEntry> entries;
  std::string text;
};

/// The largest value an MTL statement may hold: albedos and the transmission filter at most 1 (no surface reflects or
/// passes more light than it gets); emission and shininess capped far beyond real scenes, so that no estimate
/// overflows float; an index of refraction at most 10 (diamond's is 2.4).
float mtl_maximum(std::string_view keyword);

/// Whether `illum` names one of the MTL's illumination models (0-10).
inline bool known_illum(int illum) { return illum >= 0 && illum <= 10; }

/// Checks the Kd/Ks/Ke/Ns/Tf/Ni/illum values of one MTL text, adding a warning per bad value; returns the materials
/// in tinyobjloader's order so the one-value forms, a missing Ni and an unknown illum can be repaired.
std::vector<MtlEntry> scan_mtl(const MtlSource& source, std::vector<std::string>& warnings);

/// Scans every source (per file, for line numbers) and concatenates them in order: tinyobjloader reads one stream.
/// A source with binary data is left out with a warning, and its faces end up grey.
MtlStream merge_mtl_sources(const std::vector<MtlSource>& sources, std::vector<std::string>& warnings);

}  // namespace lueur::obj
