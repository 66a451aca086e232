// The MTL scan: checks the Kd/Ks/Ke/Ns values of each MTL text with file:line warnings (tinyobjloader silently
// reads junk as 0 and "Kd 0.5" as (0.5, 0, 0)), skips binary MTL files, and joins the rest into the one stream
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

/// One `newmtl` as tinyobjloader will see it; ordinal k here is the k-th named material it returns.
struct MtlEntry {
  std::string name;
  bool single_value[3] = {false, false, false};  ///< Kd, Ks, Ke given as one grey value
  bool has_ns = false;  ///< an Ns statement was given (tinyobjloader reads a missing one as 1; Lueur takes 0)
};

/// The MTL files of a scene as tinyobjloader reads them: one text, and its materials in order.
struct MtlStream {
  std::vector<MtlEntry> entries;
  std::string text;
};

/// The largest value an MTL statement may hold: albedos at most 1 (no surface reflects more light than it gets);
/// emission and shininess capped far beyond real scenes, so that no estimate overflows float.
float mtl_maximum(std::string_view keyword);

/// Checks the Kd/Ks/Ke/Ns values of one MTL text, adding a warning per bad value; returns the materials in
/// tinyobjloader's order so the one-value forms can be repaired.
std::vector<MtlEntry> scan_mtl(const MtlSource& source, std::vector<std::string>& warnings);

/// Scans every source (per file, for line numbers) and concatenates them in order: tinyobjloader reads one stream.
/// A source with binary data is left out with a warning, and its faces end up grey.
MtlStream merge_mtl_sources(const std::vector<MtlSource>& sources, std::vector<std::string>& warnings);

}  // namespace lueur::obj
