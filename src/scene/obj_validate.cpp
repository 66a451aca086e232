// The OBJ validator (see obj_validate.h): one function per kind of statement, each failing with "file:line: ..." on
// what tinyobjloader would misread, and the running memory check.
// Depends on core, obj_loader.h (scene_memory_bytes, SceneError) and obj_text.h only; never on tinyobjloader.
#include "scene/obj_validate.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "scene/obj_loader.h"
#include "scene/obj_text.h"

namespace lueur::obj {
namespace {

using std::string_view;

constexpr string_view kKnownStatements[] = {
    "v",      "vn",     "vt",     "vp",         "f",         "l",     "p",     "g",     "o",        "s",
    "usemtl", "mtllib", "cstype", "deg",        "bmat",      "step",  "curv",  "curv2", "surf",     "parm",
    "trim",   "hole",   "scrv",   "sp",         "end",       "con",   "mg",    "bevel", "c_interp", "d_interp",
    "lod",    "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call",  "csh"};

bool is_known_statement(string_view keyword) {
  return std::find(std::begin(kKnownStatements), std::end(kKnownStatements), keyword) != std::end(kKnownStatements);
}

/// About 8 s of ear clipping on one core (see check_element).
constexpr uint64_t kMaxTriangulationWork = 4'000'000'000;

/// Vertex and triangle indices are int in tinyobjloader and uint32_t (with one reserved value) in Scene.
constexpr uint64_t kMaxElements = 0x7fffffff;

/// The line being checked, and what the memory check needs.
struct LineContext {
  const std::string& label;
  size_t line;
  uint64_t text_bytes;
  const MemoryBudget& budget;
};

/// Refuses, at the line where it happens, a scene whose counts so far need more memory than the budget.
void check_scene_size(const ObjSummary& s, const LineContext& at) {
  if (s.vertices > kMaxElements || s.expected_triangles > kMaxElements)
    fail_at(at.label, at.line, "scene too large: more than " + std::to_string(kMaxElements) + " vertices or triangles");
  const uint64_t needed = scene_memory_bytes(at.text_bytes, s.vertices, s.normals, s.texcoords, s.expected_triangles);
  if (needed > at.budget.bytes) {
    std::string what = std::to_string(s.vertices);
    what += " vertices and ";
    what += std::to_string(s.expected_triangles);
    what += " triangles by this line need";
    fail_at(at.label, at.line, too_large(what, needed, at.budget));
  }
}

/// Refuses a line holding a byte that no text OBJ has.
void check_text_bytes(string_view raw, const LineContext& at) {
  for (char c : raw) {
    if (is_binary_byte(static_cast<unsigned char>(c))) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(c));
      fail_at(at.label, at.line, std::string("binary data (byte ") + byte + "): not an OBJ text file");
    }
  }
}

/// `v x y z [more]`: three finite coordinates; anything after them must still be numbers.
void check_vertex(string_view rest, ObjSummary& s, const LineContext& at) {
  float xyz[3];
  for (int i = 0; i < 3; ++i) {
    const string_view token = next_token(rest);
    if (token.empty() || token.front() == '#') fail_at(at.label, at.line, "vertex needs three coordinates");
    const NumberStatus status = parse_float(token, xyz[i]);
    if (status == NumberStatus::not_finite)
      fail_at(at.label, at.line, "vertex coordinate '" + printable(token) + "' is not a finite number");
    if (status == NumberStatus::not_a_number)
      fail_at(at.label, at.line, "vertex coordinate '" + printable(token) + "' is not a number");
  }
  // Extra values (w, or the r g b colour extension) must still be numbers; a '#' starts a comment.
  for (string_view token = next_token(rest); !token.empty() && token.front() != '#'; token = next_token(rest)) {
    float ignored = 0.0f;
    if (parse_float(token, ignored) == NumberStatus::not_a_number)
      fail_at(at.label, at.line, "unexpected '" + printable(token) + "' after vertex coordinates");
  }
  ++s.vertices;
  check_scene_size(s, at);
}

/// `vn x y z`: the values stay unchecked, since a zero or non-finite normal only falls back to the geometric
/// normal. The three tokens are required so that tinyobjloader counts the line exactly as we do.
void check_normal(string_view rest, ObjSummary& s, const LineContext& at) {
  if (next_token(rest).empty() || next_token(rest).empty() || next_token(rest).empty())
    fail_at(at.label, at.line, "normal needs three components");
  ++s.normals;
  check_scene_size(s, at);
}

/// `vt u [v [w]]`: at least one value.
void check_texcoord(string_view rest, ObjSummary& s, const LineContext& at) {
  if (trim(rest).empty()) fail_at(at.label, at.line, "texture coordinate needs a value");
  ++s.texcoords;
  check_scene_size(s, at);
}

/// Checks one face/line/point vertex reference ("i", "i/j", "i//k", "i/j/k") against the counts so far.
void check_vertex_reference(string_view token, const char* what, const ObjSummary& s, const LineContext& at,
                            bool& has_normal) {
  string_view parts[3];
  size_t part_count = 0;
  string_view rest = token;
  while (true) {
    const size_t slash = rest.find('/');
    if (part_count == 3) fail_at(at.label, at.line, std::string("bad ") + what + " vertex '" + printable(token) + "'");
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
      fail_at(at.label, at.line,
              std::string("bad ") + what + " vertex '" + printable(token) + "' (not an integer index)");
    const long long count = static_cast<long long>(slots[i].count);
    if (status == NumberStatus::not_finite || index > count || index < -count)
      fail_at(at.label, at.line,
              std::string(what) + slots[i].kind + " index " + printable(parts[i]) + " out of range (file has " +
                  std::to_string(count) + " " + slots[i].noun + " so far)");
    if (index == 0)
      fail_at(at.label, at.line,
              std::string(what) + slots[i].kind + " index 0 in '" + printable(token) + "' (OBJ indices start at 1)");
    if (i == 2) has_normal = true;
  }
}

/// `f`, `l` or `p`: every reference in range and enough of them; a face also adds its triangles, and refuses to
/// be more ear clipping than a load should take.
void check_element(string_view keyword, string_view rest, bool seen_usemtl, ObjSummary& s, const LineContext& at) {
  const char* what = keyword == "f" ? "face" : keyword == "l" ? "line" : "point";
  const size_t minimum = keyword == "f" ? 3 : keyword == "l" ? 2 : 1;
  size_t count = 0;
  bool has_normal = false;
  for (string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
    check_vertex_reference(token, what, s, at, has_normal);
    ++count;
  }
  if (count < minimum)
    fail_at(at.label, at.line,
            std::string(what) + " has " + std::to_string(count) + " vert" + (count == 1 ? "ex" : "ices") +
                " (needs at least " + std::to_string(minimum) + ")");
  if (keyword != "f") return;
  // Ear clipping takes time growing with k^2: 100000 vertices took 19 s, a million would take half an hour.
  if (count > 4) s.triangulation_work += static_cast<uint64_t>(count) * count;
  if (s.triangulation_work > kMaxTriangulationWork)
    fail_at(at.label, at.line,
            "face has " + std::to_string(count) +
                " vertices: too large to triangulate in reasonable time (the squared vertex counts of "
                "large faces may add up to 4e9, one face of 63245 vertices)");
  s.expected_triangles += count - 2;
  if (!seen_usemtl) s.triangles_before_usemtl += count - 2;
  s.references_normals = s.references_normals || has_normal;
  check_scene_size(s, at);
}

}  // namespace

ObjSummary validate_obj(string_view text, const std::string& label, const MemoryBudget& budget) {
  ObjSummary s;
  bool seen_usemtl = false;
  for_each_line(text, [&](size_t line, string_view raw) {
    const LineContext at{label, line, text.size(), budget};
    check_text_bytes(raw, at);
    string_view rest = trim(raw);
    if (rest.empty() || rest.front() == '#') return;
    const string_view keyword = next_token(rest);

    if (keyword == "v") {
      check_vertex(rest, s, at);
    } else if (keyword == "vn") {
      check_normal(rest, s, at);
    } else if (keyword == "vt") {
      check_texcoord(rest, s, at);
    } else if (keyword == "f" || keyword == "l" || keyword == "p") {
      check_element(keyword, rest, seen_usemtl, s, at);
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

}  // namespace lueur::obj
