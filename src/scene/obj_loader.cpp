// OBJ/MTL loading: our own line validator first (tinyobjloader is lenient and reads bad numbers as 0 and
// out-of-range indices as memory), then tinyobjloader for the actual parse and triangulation, then conversion
// into the flat Scene with materials, normals and a default light.
// Depends on core, scene and tinyobjloader; this is the only file that includes tiny_obj_loader.h.
// Never depends on GL, the BVH or the render passes.
#include "scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <limits>
#include <optional>
#include <string_view>
#include <sys/stat.h>
#include <unistd.h>
#include <unordered_set>

namespace lueur {
namespace {

using std::string_view;

// ---- small text helpers -----------------------------------------------------------------------------------

bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// Bytes that never appear in a text OBJ/MTL: NUL, the C0 controls other than tab/CR/LF, and DEL.
bool is_binary_byte(unsigned char c) { return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f; }

string_view trim(string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

/// Splits off the next blank-separated token; `rest` keeps what follows it.
string_view next_token(string_view& rest) {
  size_t begin = 0;
  while (begin < rest.size() && is_blank(rest[begin])) ++begin;
  size_t end = begin;
  while (end < rest.size() && !is_blank(rest[end])) ++end;
  const string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return token;
}

/// A token quoted for a one-line message: control and non-ASCII bytes escaped, long tokens cut.
std::string printable(string_view token, size_t max_chars = 32) {
  std::string out;
  for (size_t i = 0; i < token.size(); ++i) {
    if (out.size() >= max_chars) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

/// Calls `visit(line_number, line)` for every line, splitting at "\n", "\r\n" and a lone "\r" exactly as
/// tinyobjloader's safeGetline does, so that our line numbers are its line numbers.
template <typename Visit>
void for_each_line(string_view text, Visit&& visit) {
  size_t line_number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = pos;
    while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    ++line_number;
    visit(line_number, text.substr(pos, end - pos));
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
    pos = end + 1;
  }
}

[[noreturn]] void fail_at(const std::string& label, size_t line, const std::string& what) {
  throw SceneError(label + ":" + std::to_string(line) + ": " + what);
}

/// "scene too large: <what> about 3.1 GiB of memory, more than the 2.0 GiB available (MemAvailable in /proc/meminfo)".
std::string too_large(const std::string& what, uint64_t needed, const MemoryBudget& budget) {
  return "scene too large: " + what + " about " + format_bytes(needed) + " of memory, more than the " +
         format_bytes(budget.bytes) + " available (" + budget.source + ")";
}

enum class NumberStatus { ok, not_a_number, not_finite };

/// Parses a whole token as a float: rejects trailing junk ("1.5abc"), NaN, infinities and values beyond float.
NumberStatus parse_float(string_view token, float& out) {
  // tinyobjloader accepts a leading '+', std::from_chars does not; "+-1" stays an error for both.
  if (token.size() > 1 && token[0] == '+' && (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.'))
    token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range && end == token.data() + token.size()) return NumberStatus::not_finite;
  if (ec != std::errc() || end != token.data() + token.size()) return NumberStatus::not_a_number;
  out = static_cast<float>(value);
  return std::isfinite(out) ? NumberStatus::ok : NumberStatus::not_finite;
}

/// Parses a whole token as an integer; not_finite stands for "beyond long long".
NumberStatus parse_integer(string_view token, long long& out) {
  if (token.size() > 1 && token[0] == '+' && std::isdigit(static_cast<unsigned char>(token[1]))) token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  if (end != token.data() + token.size() || token.empty()) return NumberStatus::not_a_number;
  if (ec == std::errc::result_out_of_range) return NumberStatus::not_finite;
  return ec == std::errc() ? NumberStatus::ok : NumberStatus::not_a_number;
}

// ---- OBJ validation ---------------------------------------------------------------------------------------

constexpr string_view kKnownStatements[] = {
    "v",     "vn",   "vt",   "vp",      "f",       "l",        "p",    "g",      "o",      "s",
    "usemtl", "mtllib", "cstype", "deg", "bmat",  "step",     "curv", "curv2",  "surf",   "parm",
    "trim",  "hole", "scrv", "sp",      "end",     "con",      "mg",   "bevel",  "c_interp", "d_interp",
    "lod",   "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call", "csh"};

bool is_known_statement(string_view keyword) {
  return std::find(std::begin(kKnownStatements), std::end(kKnownStatements), keyword) != std::end(kKnownStatements);
}

struct MtlLib {
  std::string names;  ///< everything after `mtllib`, trimmed (one name with spaces, or several names)
  size_t line = 0;
};

struct UseMtl {
  std::string name;
  size_t line = 0;
  bool after_mtllib = false;  ///< tinyobjloader only knows materials from mtllib lines above the usemtl
};

/// What the validator learnt on its way through the file.
struct ObjSummary {
  size_t vertices = 0, normals = 0, texcoords = 0;
  size_t expected_triangles = 0;         ///< k - 2 per face with k vertices
  uint64_t triangulation_work = 0;       ///< k^2 summed over faces with k > 4 (tinyobjloader's ear clipping)
  size_t triangles_before_usemtl = 0;    ///< faces that tinyobjloader gives material -1
  bool references_normals = false;
  std::vector<MtlLib> mtllibs;
  std::vector<UseMtl> usemtls;
  std::vector<std::string> warnings;
};

/// Checks one face/line/point vertex reference ("i", "i/j", "i//k", "i/j/k") against the counts so far.
void check_vertex_reference(string_view token, const char* what, const ObjSummary& s, const std::string& label,
                            size_t line, bool& has_normal) {
  string_view parts[3];
  size_t part_count = 0;
  string_view rest = token;
  while (true) {
    const size_t slash = rest.find('/');
    if (part_count == 3) fail_at(label, line, std::string("bad ") + what + " vertex '" + printable(token) + "'");
    parts[part_count++] = rest.substr(0, slash);
    if (slash == string_view::npos) break;
    rest.remove_prefix(slash + 1);
  }
  struct Slot {
    const char* kind;
    const char* noun;
    size_t count;
  };
  const Slot slots[3] = {{"", "vertices", s.vertices},
                         {" texture", "texture coordinates", s.texcoords},
                         {" normal", "normals", s.normals}};
  for (size_t i = 0; i < part_count; ++i) {
    // Only the texture slot of "i//k" may be empty; tinyobjloader reads any other empty slot as index 0.
    if (parts[i].empty() && i == 1 && part_count == 3) continue;
    long long index = 0;
    const NumberStatus status = parse_integer(parts[i], index);
    if (status == NumberStatus::not_a_number)
      fail_at(label, line, std::string("bad ") + what + " vertex '" + printable(token) + "' (not an integer index)");
    const long long count = static_cast<long long>(slots[i].count);
    if (status == NumberStatus::not_finite || index > count || index < -count)
      fail_at(label, line,
              std::string(what) + slots[i].kind + " index " + printable(parts[i]) + " out of range (file has " +
                  std::to_string(count) + " " + slots[i].noun + " so far)");
    if (index == 0)
      fail_at(label, line,
              std::string(what) + slots[i].kind + " index 0 in '" + printable(token) + "' (OBJ indices start at 1)");
    if (i == 2) has_normal = true;
  }
}

/// About 8 s of ear clipping on one core (see validate_obj).
constexpr uint64_t kMaxTriangulationWork = 4'000'000'000;

/// Vertex and triangle indices are int in tinyobjloader and uint32_t (with one reserved value) in Scene.
constexpr uint64_t kMaxElements = 0x7fffffff;

/// Refuses, at the line where it happens, a scene whose counts so far need more memory than the budget.
void check_scene_size(const ObjSummary& s, uint64_t text_bytes, const MemoryBudget& budget, const std::string& label,
                      size_t line) {
  if (s.vertices > kMaxElements || s.expected_triangles > kMaxElements)
    fail_at(label, line, "scene too large: more than " + std::to_string(kMaxElements) + " vertices or triangles");
  const uint64_t needed = scene_memory_bytes(text_bytes, s.vertices, s.normals, s.texcoords, s.expected_triangles);
  if (needed > budget.bytes) {
    std::string what = std::to_string(s.vertices);
    what += " vertices and ";
    what += std::to_string(s.expected_triangles);
    what += " triangles by this line need";
    fail_at(label, line, too_large(what, needed, budget));
  }
}

ObjSummary validate_obj(string_view text, const std::string& label, const MemoryBudget& budget) {
  ObjSummary s;
  bool seen_usemtl = false;
  for_each_line(text, [&](size_t line, string_view raw) {
    for (char c : raw) {
      if (is_binary_byte(static_cast<unsigned char>(c))) {
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(c));
        fail_at(label, line, std::string("binary data (byte ") + byte + "): not an OBJ text file");
      }
    }
    string_view rest = trim(raw);
    if (rest.empty() || rest.front() == '#') return;
    const string_view keyword = next_token(rest);

    if (keyword == "v") {
      float xyz[3];
      for (int i = 0; i < 3; ++i) {
        const string_view token = next_token(rest);
        if (token.empty() || token.front() == '#') fail_at(label, line, "vertex needs three coordinates");
        const NumberStatus status = parse_float(token, xyz[i]);
        if (status == NumberStatus::not_finite)
          fail_at(label, line, "vertex coordinate '" + printable(token) + "' is not a finite number");
        if (status == NumberStatus::not_a_number)
          fail_at(label, line, "vertex coordinate '" + printable(token) + "' is not a number");
      }
      // Extra values (w, or the r g b colour extension) must still be numbers; a '#' starts a comment.
      for (string_view token = next_token(rest); !token.empty() && token.front() != '#'; token = next_token(rest)) {
        float ignored = 0.0f;
        if (parse_float(token, ignored) == NumberStatus::not_a_number)
          fail_at(label, line, "unexpected '" + printable(token) + "' after vertex coordinates");
      }
      ++s.vertices;
      check_scene_size(s, text.size(), budget, label, line);
    } else if (keyword == "vn") {
      // Values stay unchecked: a zero or non-finite normal only falls back to the geometric normal. The three
      // tokens are required so that tinyobjloader counts the line exactly as we do.
      string_view copy = rest;
      if (next_token(copy).empty() || next_token(copy).empty() || next_token(copy).empty())
        fail_at(label, line, "normal needs three components");
      ++s.normals;
      check_scene_size(s, text.size(), budget, label, line);
    } else if (keyword == "vt") {
      if (trim(rest).empty()) fail_at(label, line, "texture coordinate needs a value");
      ++s.texcoords;
      check_scene_size(s, text.size(), budget, label, line);
    } else if (keyword == "f" || keyword == "l" || keyword == "p") {
      const char* what = keyword == "f" ? "face" : keyword == "l" ? "line" : "point";
      const size_t minimum = keyword == "f" ? 3 : keyword == "l" ? 2 : 1;
      size_t count = 0;
      bool has_normal = false;
      for (string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
        check_vertex_reference(token, what, s, label, line, has_normal);
        ++count;
      }
      if (count < minimum)
        fail_at(label, line, std::string(what) + " has " + std::to_string(count) + " vert" +
                                 (count == 1 ? "ex" : "ices") + " (needs at least " + std::to_string(minimum) + ")");
      if (keyword == "f") {
        // Ear clipping takes time growing with k^2: 100000 vertices took 19 s, a million would take half an hour.
        if (count > 4) s.triangulation_work += static_cast<uint64_t>(count) * count;
        if (s.triangulation_work > kMaxTriangulationWork)
          fail_at(label, line,
                  "face has " + std::to_string(count) +
                      " vertices: too large to triangulate in reasonable time (the squared vertex counts of "
                      "large faces may add up to 4e9, one face of 63245 vertices)");
        s.expected_triangles += count - 2;
        if (!seen_usemtl) s.triangles_before_usemtl += count - 2;
        s.references_normals = s.references_normals || has_normal;
        check_scene_size(s, text.size(), budget, label, line);
      }
    } else if (keyword == "usemtl") {
      seen_usemtl = true;
      s.usemtls.push_back({std::string(next_token(rest)), line, !s.mtllibs.empty()});
    } else if (keyword == "mtllib") {
      const string_view names = trim(rest);
      if (names.empty()) {
        s.warnings.push_back(label + ":" + std::to_string(line) + ": mtllib without a file name");
      } else {
        s.mtllibs.push_back({std::string(names), line});
      }
    } else if (!is_known_statement(keyword)) {
      fail_at(label, line, "unknown statement '" + printable(keyword) + "'");
    }
  });
  return s;
}

// ---- MTL scanning -----------------------------------------------------------------------------------------

/// One MTL text and the name it is reported under.
struct MtlSource {
  std::string label;
  std::string text;
};

/// One `newmtl` as tinyobjloader will see it; ordinal k here is the k-th named material it returns.
struct MtlEntry {
  std::string name;
  bool single_value[3] = {false, false, false};  ///< Kd, Ks, Ke given as one grey value
};

/// The largest value an MTL statement may hold: albedos at most 1 (no surface reflects more light than it gets);
/// emission and shininess capped far beyond real scenes, so that no estimate overflows float.
float mtl_maximum(string_view keyword) { return keyword == "Kd" || keyword == "Ks" ? 1.0f : 1e6f; }

/// Checks the Kd/Ks/Ke/Ns values of an MTL text (tinyobjloader silently reads junk as 0 and "Kd 0.5" as
/// (0.5, 0, 0)); returns the materials in tinyobjloader's order so the one-value forms can be repaired.
std::vector<MtlEntry> scan_mtl(const MtlSource& source, std::vector<std::string>& warnings) {
  std::vector<MtlEntry> entries;
  for_each_line(source.text, [&](size_t line, string_view raw) {
    // Same statement detection as tinyobjloader's LoadMtl: trailing blanks trimmed, then leading blanks skipped.
    while (!raw.empty() && is_blank(raw.back())) raw.remove_suffix(1);
    while (!raw.empty() && is_blank(raw.front())) raw.remove_prefix(1);
    if (raw.size() > 7 && raw.substr(0, 6) == "newmtl" && is_blank(raw[6])) {
      entries.push_back({std::string(raw.substr(7)), {false, false, false}});
      return;
    }
    if (raw.size() < 3 || !is_blank(raw[2])) return;
    const string_view keyword = raw.substr(0, 2);
    int slot = -1;
    if (keyword == "Kd") slot = 0;
    else if (keyword == "Ks") slot = 1;
    else if (keyword == "Ke") slot = 2;
    else if (keyword != "Ns") return;
    string_view rest = raw.substr(3);
    const size_t wanted = slot < 0 ? 1 : 3;
    size_t given = 0;
    const size_t warnings_before = warnings.size();
    auto warn = [&](const std::string& message) {  // "Ke 1e39 1e39 1e39" is one problem, said once
      if (std::find(warnings.begin() + static_cast<std::ptrdiff_t>(warnings_before), warnings.end(), message) ==
          warnings.end())
        warnings.push_back(message);
    };
    for (string_view token = next_token(rest); !token.empty() && given < wanted; token = next_token(rest), ++given) {
      float value = 0.0f;
      const NumberStatus status = parse_float(token, value);
      const std::string where = source.label + ":" + std::to_string(line) + ": ";
      if (status != NumberStatus::ok) {
        warn(where + std::string(keyword) + " value '" + printable(token) + "' is not a " +
             (status == NumberStatus::not_finite ? "finite number" : "number") + ": using 0");
      } else if (value < 0.0f) {
        warn(where + "negative " + std::string(keyword) + " value " + printable(token) + " clamped to 0");
      } else if (value > mtl_maximum(keyword)) {
        char maximum[32];
        std::snprintf(maximum, sizeof maximum, "%g", static_cast<double>(mtl_maximum(keyword)));
        warn(where + std::string(keyword) + " value " + printable(token) + " above " + maximum + " clamped to " +
             maximum);
      }
    }
    if (slot >= 0 && given == 1 && !entries.empty()) entries.back().single_value[slot] = true;
  });
  return entries;
}

// ---- files ------------------------------------------------------------------------------------------------

/// Reads a whole regular file; throws SceneError "cannot open 'path': reason". FIFOs, devices and directories
/// are refused (a FIFO would block, /dev/zero never ends), and so is a file too large for the memory budget.
std::string read_text_file(const std::string& path, const MemoryBudget& budget) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw SceneError("cannot open '" + path + "': " + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    const int why = errno;
    ::close(fd);
    throw SceneError("cannot open '" + path + "': " + std::strerror(why));
  }
  if (!S_ISREG(info.st_mode)) {
    ::close(fd);
    throw SceneError("cannot open '" + path + "': " +
                     (S_ISDIR(info.st_mode) ? std::string(std::strerror(EISDIR)) : std::string("not a regular file")));
  }
  const uint64_t size = static_cast<uint64_t>(info.st_size);
  if (const uint64_t needed = scene_memory_bytes(size, 0, 0, 0, 0); needed > budget.bytes) {
    ::close(fd);
    throw SceneError(path + ": " + too_large("a " + format_bytes(size) + " file needs", needed, budget));
  }
  std::string text;
  text.reserve(static_cast<size_t>(size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int why = errno;
      ::close(fd);
      throw SceneError("cannot read '" + path + "': " + std::strerror(why));
    }
    text.append(buffer, static_cast<size_t>(n));
    // A file that grows while it is read is held to the same budget.
    if (text.size() > size && scene_memory_bytes(text.size(), 0, 0, 0, 0) > budget.bytes) {
      ::close(fd);
      throw SceneError(path + ": " +
                       too_large("a file growing past " + format_bytes(text.size()) + " needs",
                                 scene_memory_bytes(text.size(), 0, 0, 0, 0), budget));
    }
  }
  ::close(fd);
  return text;
}

/// A UTF-8 byte-order mark would make tinyobjloader skip the first statement; it carries no meaning in OBJ.
void strip_bom(std::string& text) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
}

/// The file names of an mtllib line: blank-separated, with "\\ " keeping a blank inside a name (the same
/// escape tinyobjloader honours).
std::vector<std::string> split_mtllib(string_view s) {
  std::vector<std::string> names;
  std::string current;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size()) {
      current += s[++i];
    } else if (is_blank(s[i])) {
      if (!current.empty()) names.push_back(std::move(current));
      current.clear();
    } else {
      current += s[i];
    }
  }
  if (!current.empty()) names.push_back(std::move(current));
  return names;
}

/// Reads the MTL files named by the mtllib lines, beside the OBJ file. Unreadable ones become warnings.
std::vector<MtlSource> read_mtl_files(const std::string& obj_path, const std::string& label, const ObjSummary& s,
                                      const MemoryBudget& budget, std::vector<std::string>& warnings) {
  namespace fs = std::filesystem;
  const fs::path directory = fs::path(obj_path).parent_path();
  std::vector<MtlSource> sources;
  std::unordered_set<std::string> seen;
  for (const MtlLib& lib : s.mtllibs) {
    // A single name with spaces is tried first; otherwise the line lists several names.
    std::vector<std::string> names{lib.names};
    std::error_code ec;
    if (!fs::exists(directory / lib.names, ec)) names = split_mtllib(lib.names);
    for (const std::string& name : names) {
      if (!seen.insert(name).second) continue;
      const std::string mtl_path = (directory / name).string();
      try {
        MtlSource source{name, read_text_file(mtl_path, budget)};
        strip_bom(source.text);
        sources.push_back(std::move(source));
      } catch (const SceneError& e) {
        warnings.push_back(label + ":" + std::to_string(lib.line) + ": " + e.what() + ": using grey diffuse");
      }
    }
  }
  return sources;
}

// ---- conversion -------------------------------------------------------------------------------------------

/// NaN and negative values become 0, values above `maximum` become `maximum`.
float clamp_value(float v, float maximum) { return std::isfinite(v) && v > 0.0f ? std::min(v, maximum) : 0.0f; }

Vec3 clamp_value(const Vec3& v, float maximum) {
  return Vec3(clamp_value(v.x, maximum), clamp_value(v.y, maximum), clamp_value(v.z, maximum));
}

/// "1 triangle", "2 triangles".
std::string counted(size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string scene_name_of(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  return stem.empty() ? path : stem;
}

/// Parses validated text with tinyobjloader and builds the Scene.
LoadedScene build_scene(const std::string& obj_text, const std::string& label, const std::string& scene_name,
                        ObjSummary& summary, std::vector<MtlSource> mtl_sources, const LoadOptions& options) {
  LoadedScene result;
  std::vector<std::string>& warnings = result.warnings;
  warnings = std::move(summary.warnings);

  // MTL values are checked per file (for line numbers), then concatenated: tinyobjloader reads one stream.
  std::vector<MtlEntry> mtl_entries;
  std::string mtl_text;
  for (MtlSource& source : mtl_sources) {
    bool binary = false;
    size_t binary_line = 0;
    for_each_line(source.text, [&](size_t line, string_view raw) {
      if (binary) return;
      for (char c : raw) {
        if (is_binary_byte(static_cast<unsigned char>(c))) {
          binary = true;
          binary_line = line;
          return;
        }
      }
    });
    if (binary) {
      warnings.push_back(source.label + ":" + std::to_string(binary_line) +
                         ": binary data: material file ignored, using grey diffuse");
      continue;
    }
    std::vector<MtlEntry> entries = scan_mtl(source, warnings);
    mtl_entries.insert(mtl_entries.end(), entries.begin(), entries.end());
    mtl_text += source.text;
    if (!mtl_text.empty() && mtl_text.back() != '\n') mtl_text += '\n';
  }

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  const bool parsed = reader.ParseFromString(obj_text, mtl_text, config);
  if (!parsed || !reader.Error().empty()) {
    std::string error = reader.Error();
    error = error.substr(0, error.find('\n'));
    throw SceneError(label + ": " + (error.empty() ? std::string("tinyobjloader could not parse the file") : error));
  }
  {
    // Its "material not found" lines are replaced by ours, which name the line. Its MTL warnings end in
    // "(line N in .mtl.)" and are labelled with the MTL file when there is only one.
    std::string_view text = reader.Warning();
    std::unordered_set<std::string> seen;
    for_each_line(text, [&](size_t, string_view line) {
      line = trim(line);
      if (line.empty() || line == "." || line.substr(0, 12) == "material [ '") return;
      const bool about_mtl = line.find("in .mtl") != string_view::npos && mtl_sources.size() == 1;
      const std::string& where = about_mtl ? mtl_sources.front().label : label;
      if (seen.insert(std::string(line)).second) warnings.push_back(where + ": " + std::string(line));
    });
  }

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  Scene& scene = result.scene;
  scene.name = scene_name;

  const size_t vertex_count = attrib.vertices.size() / 3;
  scene.positions.reserve(vertex_count + 4);
  for (size_t i = 0; i < vertex_count; ++i)
    scene.positions.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);

  // File normals, normalised; unusable ones (zero, NaN, overflow) leave their corners on the geometric normal.
  const size_t normal_count = attrib.normals.size() / 3;
  std::vector<uint32_t> normal_remap(normal_count, kNoNormal);
  size_t unusable_normals = 0;
  for (size_t i = 0; i < normal_count; ++i) {
    const Vec3 n(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
    const float length = glm::length(n);
    if (length > 0.0f && std::isfinite(length) && is_finite(n / length)) {
      normal_remap[i] = static_cast<uint32_t>(scene.normals.size());
      scene.normals.push_back(n / length);
    } else {
      ++unusable_normals;
    }
  }
  if (unusable_normals > 0)
    warnings.push_back(label + ": " + counted(unusable_normals, "unusable normal") +
                       " (zero or not finite): the geometric normal is used there");

  // Materials: tinyobjloader also returns nameless ones (an empty MTL, a second mtllib); those are dropped and
  // their faces, like faces with material -1, get the grey default.
  const std::vector<tinyobj::material_t>& file_materials = reader.GetMaterials();
  const bool entries_match =
      mtl_entries.size() == static_cast<size_t>(std::count_if(file_materials.begin(), file_materials.end(),
                                                              [](const auto& m) { return !m.name.empty(); }));
  std::vector<int64_t> material_remap(file_materials.size(), -1);
  std::unordered_set<std::string> known_names;
  size_t named = 0;
  for (size_t i = 0; i < file_materials.size(); ++i) {
    const tinyobj::material_t& m = file_materials[i];
    if (m.name.empty()) continue;
    Material material;
    material.name = m.name;
    material.kd = Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    material.ks = Vec3(m.specular[0], m.specular[1], m.specular[2]);
    material.ke = Vec3(m.emission[0], m.emission[1], m.emission[2]);
    material.ns = m.shininess;
    if (entries_match) {
      const MtlEntry& entry = mtl_entries[named];
      if (entry.single_value[0]) material.kd = Vec3(material.kd.r);
      if (entry.single_value[1]) material.ks = Vec3(material.ks.r);
      if (entry.single_value[2]) material.ke = Vec3(material.ke.r);
    }
    ++named;
    // The scan above already warned, with file and line, about every value clamped here.
    material.kd = clamp_value(material.kd, mtl_maximum("Kd"));
    material.ks = clamp_value(material.ks, mtl_maximum("Ks"));
    material.ke = clamp_value(material.ke, mtl_maximum("Ke"));
    material.ns = clamp_value(material.ns, mtl_maximum("Ns"));
    material_remap[i] = static_cast<int64_t>(scene.materials.size());
    known_names.insert(m.name);
    scene.materials.push_back(material);
  }
  std::optional<uint32_t> default_material;  // appended on first use only
  size_t default_triangles = 0;
  auto default_material_index = [&]() {
    if (!default_material) {
      Material grey;  // kd 0.5, nothing else
      if (known_names.count(grey.name)) grey.name = "lueur-default";
      default_material = static_cast<uint32_t>(scene.materials.size());
      scene.materials.push_back(grey);
    }
    ++default_triangles;
    return *default_material;
  };

  auto checked_index = [&](int index, size_t count) -> uint32_t {
    // The validator makes this unreachable; it guards against tinyobjloader disagreeing with it.
    if (index < 0 || static_cast<size_t>(index) >= count)
      throw SceneError(label + ": face refers to a missing vertex (index " + std::to_string(index) + ")");
    return static_cast<uint32_t>(index);
  };
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t corners = mesh.num_face_vertices[f];
      if (corners == 3 && offset + 3 <= mesh.indices.size()) {
        Triangle tri;
        for (size_t c = 0; c < 3; ++c) {
          const tinyobj::index_t& index = mesh.indices[offset + c];
          tri.v[c] = checked_index(index.vertex_index, vertex_count);
          if (index.normal_index >= 0) tri.n[c] = normal_remap[checked_index(index.normal_index, normal_count)];
        }
        const int id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
        const int64_t mapped = id >= 0 && static_cast<size_t>(id) < material_remap.size() ? material_remap[id] : -1;
        tri.material = mapped >= 0 ? static_cast<uint32_t>(mapped) : default_material_index();
        scene.triangles.push_back(tri);
      }
      offset += corners;
    }
  }

  if (scene.triangles.empty()) {
    if (summary.expected_triangles > 0)
      throw SceneError(label + ": no triangles: triangulating its faces gave none (degenerate polygons)");
    throw SceneError(label + ": no triangles");
  }
  if (scene.triangles.size() < summary.expected_triangles) {
    warnings.push_back(label + ": " + counted(summary.expected_triangles - scene.triangles.size(), "triangle") +
                       " of polygons lost in triangulation");
  }

  // Why faces ended up grey.
  if (default_triangles > 0) {
    if (summary.mtllibs.empty()) {
      warnings.push_back(label + ": no materials: using grey diffuse");
    } else {
      if (summary.triangles_before_usemtl > 0)
        warnings.push_back(label + ": " + counted(summary.triangles_before_usemtl, "triangle") +
                           " before the first usemtl: using grey diffuse");
      std::unordered_set<std::string> reported;
      size_t unreported = 0;
      for (const UseMtl& use : summary.usemtls) {
        if (use.after_mtllib && known_names.count(use.name)) continue;
        if (!reported.insert(use.name).second) continue;
        if (reported.size() > 5) {
          ++unreported;
          continue;
        }
        warnings.push_back(label + ":" + std::to_string(use.line) + ": unknown material '" + printable(use.name) +
                           "': using grey diffuse");
      }
      if (unreported > 0)
        warnings.push_back(label + ": " + counted(unreported, "more unknown material") + ": using grey diffuse");
    }
  }

  size_t zero_area = 0, zero_area_emitters = 0, overflowing = 0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const float area = scene.area(t);
    if (!(area > 0.0f)) {
      ++zero_area;
      if (scene.material_of(t).emissive()) ++zero_area_emitters;
    } else if (!std::isfinite(area)) {
      ++overflowing;  // edges beyond about 1e19: their cross product overflows float
    }
  }
  if (zero_area > 0) {
    std::string message = label + ": " + counted(zero_area, "zero-area triangle") + " (kept; never lights";
    if (zero_area_emitters > 0) {
      message += "; ";
      message += std::to_string(zero_area_emitters);
      message += " of them emissive";
    }
    message += ')';
    warnings.push_back(message);
  }
  if (overflowing > 0)
    warnings.push_back(label + ": " + counted(overflowing, "triangle") +
                       " too large for float arithmetic (area overflows; kept, never lights)");

  // File normals are the author's; computed ones only stand in when there are none.
  if (!summary.references_normals) {
    if (options.smooth_normals) {
      compute_smooth_normals(scene, options.crease_degrees);
    } else {
      clear_normals(scene);
    }
  }

  collect_emitters(scene);
  if (scene.emitters.empty()) {
    add_default_light(scene);
    warnings.push_back(label + ": no emitter: added a default area light above the scene");
    collect_emitters(scene);
    // Around 1e20 and beyond, float spacing swallows any light small enough for its area to stay finite.
    if (scene.emitters.empty()) {
      const Box3 box = scene.bounds();
      char extent[64];
      std::snprintf(extent, sizeof extent, "%g", static_cast<double>(std::max(max_abs_component(box.lo),
                                                                                   max_abs_component(box.hi))));
      throw SceneError(label + ": no emitter, and coordinates up to " + extent +
                       " are too large for float to hold a default light");
    }
  }
  return result;
}

}  // namespace

uint64_t scene_memory_bytes(uint64_t text_bytes, uint64_t vertices, uint64_t normals, uint64_t texcoords,
                            uint64_t triangles) {
  // Fitted to measured peaks with about 1.6x to spare: a 1000x1000 grid OBJ (68 MB, 1M vertices, 2M triangles,
  // smooth normals computed) peaked at 489 MB resident and is budgeted 765 MB; a 62 MB triangle soup (2.1M
  // vertices, 0.7M triangles) peaked at 279 MB and is budgeted 467 MB. The text is held more than once (the
  // file, tinyobjloader's stream); triangles cost most: tinyobjloader's indices, the Scene, normals, the BVH.
  constexpr uint64_t kPerTextByte = 3, kPerVertex = 48, kPerNormal = 32, kPerTexcoord = 24, kPerTriangle = 256;
  const uint64_t parts[][2] = {{text_bytes, kPerTextByte},
                               {vertices, kPerVertex},
                               {normals, kPerNormal},
                               {texcoords, kPerTexcoord},
                               {triangles, kPerTriangle}};
  uint64_t total = 0;
  for (const auto& [count, bytes] : parts) {
    uint64_t part = 0;
    if (__builtin_mul_overflow(count, bytes, &part) || __builtin_add_overflow(total, part, &total))
      return std::numeric_limits<uint64_t>::max();  // a sparse file of exabytes must not wrap around to a small figure
  }
  return total;
}

LoadedScene load_obj(const std::string& path, const LoadOptions& options) {
  const MemoryBudget budget = options.memory ? *options.memory : available_memory();
  std::string text = read_text_file(path, budget);
  strip_bom(text);
  ObjSummary summary = validate_obj(text, path, budget);
  std::vector<std::string> mtl_warnings;
  std::vector<MtlSource> sources = read_mtl_files(path, path, summary, budget, mtl_warnings);
  summary.warnings.insert(summary.warnings.end(), mtl_warnings.begin(), mtl_warnings.end());
  return build_scene(text, path, scene_name_of(path), summary, std::move(sources), options);
}

LoadedScene load_obj_from_text(const std::string& obj_text, const std::string& mtl_text, const std::string& name,
                               const LoadOptions& options) {
  const MemoryBudget budget = options.memory ? *options.memory : available_memory();
  std::string text = obj_text;
  strip_bom(text);
  ObjSummary summary = validate_obj(text, name, budget);
  std::vector<MtlSource> sources;
  if (!summary.mtllibs.empty()) {
    const std::vector<std::string> names = split_mtllib(summary.mtllibs.front().names);
    MtlSource source{names.empty() ? scene_name_of(name) + ".mtl" : names.front(), mtl_text};
    strip_bom(source.text);
    sources.push_back(std::move(source));
  }
  return build_scene(text, name, scene_name_of(name), summary, std::move(sources), options);
}

}  // namespace lueur
