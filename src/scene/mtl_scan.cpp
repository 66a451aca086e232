// The MTL scan (see mtl_scan.h): value warnings with file and line, the one-value forms, binary files left out.
// Depends on obj_text.h only; never on tinyobjloader.
#include "scene/mtl_scan.h"

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <cstdio>

#include "scene/obj_text.h"

namespace lueur::obj {
namespace {

using std::string_view;

/// Warns about each of the first `wanted` values of a Kd/Ks/Ke/Ns/Tf/Ni statement that is not a finite number or lies
/// outside [0, mtl_maximum] (Ni: outside (0, mtl_maximum], a bad one replaced by kDefaultIor); returns how many
/// values were given, and sets `usable` false where one of them was not a number or (Ni) not positive.
size_t check_mtl_values(string_view keyword, string_view rest, size_t wanted, const std::string& where,
                        std::vector<std::string>& warnings, bool& usable) {
  size_t given = 0;
  const bool index = keyword == "Ni";
  const std::string fallback = index ? "1.5" : "0";
  const size_t warnings_before = warnings.size();
  auto warn = [&](const std::string& message) {  // "Ke 1e39 1e39 1e39" is one problem, said once
    if (std::find(warnings.begin() + static_cast<std::ptrdiff_t>(warnings_before), warnings.end(), message) ==
        warnings.end())
      warnings.push_back(message);
  };
  for (string_view token = next_token(rest); !token.empty() && given < wanted; token = next_token(rest), ++given) {
    float value = 0.0f;
    const NumberStatus status = parse_float(token, value);
    if (status != NumberStatus::ok) {
      warn(where + std::string(keyword) + " value '" + printable(token) + "' is not a " +
           (status == NumberStatus::not_finite ? "finite number" : "number") + ": using " + fallback);
      usable = false;
    } else if (index && value <= 0.0f) {
      warn(where + "Ni value " + printable(token) + " is not positive: using " + fallback);
      usable = false;
    } else if (value < 0.0f) {
      warn(where + "negative " + std::string(keyword) + " value " + printable(token) + " clamped to 0");
    } else if (value > mtl_maximum(keyword)) {
      char maximum[32];
      std::snprintf(maximum, sizeof maximum, "%g", static_cast<double>(mtl_maximum(keyword)));
      warn(where + std::string(keyword) + " value " + printable(token) + " above " + maximum + " clamped to " +
           maximum);
    }
  }
  return given;
}

/// The line of the first byte that no text MTL has; 0 when there is none.
size_t first_binary_line(string_view text) {
  size_t found = 0;
  for_each_line(text, [&](size_t line, string_view raw) {
    if (found != 0) return;
    for (char c : raw) {
      if (is_binary_byte(static_cast<unsigned char>(c))) {
        found = line;
        return;
      }
    }
  });
  return found;
}

/// Checks an `illum` statement's value: one integer from 0 to 10. Returns it, or kDefaultIllum with a warning.
int checked_illum(string_view rest, const std::string& where, std::vector<std::string>& warnings) {
  const string_view token = next_token(rest);
  float value = 0.0f;
  const bool number = parse_float(token, value) == NumberStatus::ok && value == std::floor(value);
  if (number && known_illum(static_cast<int>(value))) return static_cast<int>(value);
  warnings.push_back(where + "illum value '" + printable(token) + "' is not an illumination model (0-10): using " +
                     std::to_string(kDefaultIllum));
  return kDefaultIllum;
}

}  // namespace

float mtl_maximum(string_view keyword) {
  if (keyword == "Kd" || keyword == "Ks" || keyword == "Tf" || keyword == "Kt") return 1.0f;
  if (keyword == "Ni") return 10.0f;
  return 1e6f;
}

std::vector<MtlEntry> scan_mtl(const MtlSource& source, std::vector<std::string>& warnings) {
  std::vector<MtlEntry> entries;
  for_each_line(source.text, [&](size_t line, string_view raw) {
    // Same statement detection as tinyobjloader's LoadMtl: trailing blanks trimmed, then leading blanks skipped.
    while (!raw.empty() && is_blank(raw.back())) raw.remove_suffix(1);
    while (!raw.empty() && is_blank(raw.front())) raw.remove_prefix(1);
    if (raw.size() > 7 && raw.substr(0, 6) == "newmtl" && is_blank(raw[6])) {
      entries.push_back(MtlEntry{});
      entries.back().name = std::string(raw.substr(7));
      return;
    }
    if (raw.size() > 6 && raw.substr(0, 5) == "illum" && is_blank(raw[5])) {
      const int illum = checked_illum(raw.substr(6), source.label + ":" + std::to_string(line) + ": ", warnings);
      if (!entries.empty()) entries.back().illum = illum;
      return;
    }
    if (raw.size() < 3 || !is_blank(raw[2])) return;
    const string_view keyword = raw.substr(0, 2);
    int slot = -1;
    if (keyword == "Kd")
      slot = 0;
    else if (keyword == "Ks")
      slot = 1;
    else if (keyword == "Ke")
      slot = 2;
    else if (keyword == "Tf" || keyword == "Kt")
      slot = 3;
    else if (keyword != "Ns" && keyword != "Ni")
      return;
    const std::string where = source.label + ":" + std::to_string(line) + ": ";
    bool usable = true;
    const size_t given = check_mtl_values(keyword, raw.substr(3), slot < 0 ? 1 : 3, where, warnings, usable);
    if (entries.empty()) return;
    MtlEntry& entry = entries.back();
    if (slot >= 0 && given == 1) entry.single_value[slot] = true;
    if (keyword == "Ns") entry.has_ns = true;
    if (slot == 3) entry.has_tf = true;
    if (keyword == "Ni") entry.has_ni = given > 0 && usable;
  });
  return entries;
}

MtlStream merge_mtl_sources(const std::vector<MtlSource>& sources, std::vector<std::string>& warnings) {
  MtlStream stream;
  for (const MtlSource& source : sources) {
    if (const size_t binary_line = first_binary_line(source.text); binary_line != 0) {
      warnings.push_back(source.label + ":" + std::to_string(binary_line) +
                         ": binary data: material file ignored, using grey diffuse");
      continue;
    }
    std::vector<MtlEntry> entries = scan_mtl(source, warnings);
    stream.entries.insert(stream.entries.end(), entries.begin(), entries.end());
    stream.text += source.text;
    if (!stream.text.empty() && stream.text.back() != '\n') stream.text += '\n';
  }
  return stream;
}

}  // namespace lueur::obj
