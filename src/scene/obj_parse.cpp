// The OBJ parser (see obj_parse.h): one function per kind of statement, each refusing with "file:line: ..." what
// would be misread and keeping what the scene needs, and the running memory check.
// Depends on core, obj_loader.h (scene_memory_bytes, SceneError) and obj_text.h only.
#include "scene/obj_parse.h"

#include <algorithm>
#include <cstdio>
#include <iterator>

#include "scene/obj_loader.h"
#include "scene/obj_text.h"

namespace lueur::obj {

void ObjCounts::add(const ObjCounts& more) {
  lines += more.lines;
  vertices += more.vertices;
  normals += more.normals;
  texcoords += more.texcoords;
  faces += more.faces;
  corners += more.corners;
  triangles += more.triangles;
  triangulation_work += more.triangulation_work;
  seen_usemtl = seen_usemtl || more.seen_usemtl;
  seen_mtllib = seen_mtllib || more.seen_mtllib;
}

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

/// How often (in elements) a chunk adds what it read to the shared running total.
constexpr uint64_t kElementsPerSharedCheck = 1 << 16;

/// Throws SceneError at the line where counts `s` (with `text_bytes` of text) do not fit (scene_fits).
void check_scene_size(const ObjCounts& s, uint64_t text_bytes, const std::string& label, size_t line,
                      const MemoryBudget& budget) {
  if (scene_fits(s, text_bytes, budget)) return;
  if (s.vertices > kMaxElements || s.triangles > kMaxElements)
    fail_at(label, line, "scene too large: more than " + std::to_string(kMaxElements) + " vertices or triangles");
  std::string what = std::to_string(s.vertices);
  what += " vertices and ";
  what += std::to_string(s.triangles);
  what += " triangles by this line need";
  fail_at(label, line,
          too_large(what, scene_memory_bytes(text_bytes, s.vertices, s.normals, s.texcoords, s.triangles), budget));
}

/// One chunk being parsed: its context, its output and the line at hand.
struct ChunkParser {
  const ParseContext& context;
  ObjChunk& out;
  ObjCounts& local;  ///< out.counts
  size_t line = 0;   ///< the chunk's own line number
  uint64_t unshared = 0;
  uint64_t shared_bytes = 0;  ///< what this chunk has added to context.memory_needed
  uint64_t headroom = 0;      ///< elements of any kind that certainly still fit

  /// How many more elements of any kind fit after `counts` whatever their kind: the budget's slack over the
  /// costliest element, and the room left below the index limit.
  uint64_t elements_that_fit(const ObjCounts& counts) const {
    const uint64_t costliest = std::max({scene_memory_bytes(0, 1, 0, 0, 0), scene_memory_bytes(0, 0, 1, 0, 0),
                                         scene_memory_bytes(0, 0, 0, 1, 0), scene_memory_bytes(0, 0, 0, 0, 1)});
    const uint64_t needed =
        scene_memory_bytes(context.text_bytes, counts.vertices, counts.normals, counts.texcoords, counts.triangles);
    const uint64_t slack = (context.budget.bytes - needed) / std::max<uint64_t>(costliest, 1);
    return std::min(slack, kMaxElements - std::max(counts.vertices, counts.triangles));
  }

  /// The line as messages name it: the file's when the lines before the chunk are known.
  size_t reported_line() const { return context.before ? context.before->lines + line : line; }
  [[noreturn]] void fail(const std::string& what) const { fail_at(context.label, reported_line(), what); }

  /// The file's counts up to this line, as far as the chunk knows them.
  ObjCounts so_far() const {
    ObjCounts counts = local;
    if (context.before) counts.add(*context.before);
    return counts;
  }

  /// Refuses the line where the counts so far need more memory than the budget, or the shared total does. `added`:
  /// the elements the line added (a face's triangles). Lines within the headroom that the last full check left are
  /// known to fit without one (the estimate is linear in the counts).
  void check_size(uint64_t added) {
    if (added <= headroom) {
      headroom -= added;
    } else {
      const ObjCounts counts = so_far();
      check_scene_size(counts, context.text_bytes, context.label, reported_line(), context.budget);
      headroom = elements_that_fit(counts);
    }
    if (context.memory_needed && ++unshared == kElementsPerSharedCheck) {
      unshared = 0;
      // Every chunk's elements together, as the file's would count: the estimate is linear in the counts.
      const uint64_t mine = scene_memory_bytes(0, local.vertices, local.normals, local.texcoords, local.triangles);
      const uint64_t total = context.memory_needed->fetch_add(mine - shared_bytes) + (mine - shared_bytes);
      shared_bytes = mine;
      if (scene_memory_bytes(context.text_bytes, 0, 0, 0, 0) + total > context.budget.bytes)
        fail("scene too large: the file's elements outgrow the memory budget");
    }
  }
};

/// Refuses a line holding a byte that no text OBJ has.
void check_text_bytes(string_view raw, const ChunkParser& p) {
  for (char c : raw) {
    if (is_binary_byte(static_cast<unsigned char>(c))) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(c));
      p.fail(std::string("binary data (byte ") + byte + "): not an OBJ text file");
    }
  }
}

/// `v x y z [more]`: three finite coordinates; anything after them must still be numbers.
void parse_vertex(string_view rest, ChunkParser& p) {
  float xyz[3];
  for (int i = 0; i < 3; ++i) {
    const string_view token = next_token(rest);
    if (token.empty() || token.front() == '#') p.fail("vertex needs three coordinates");
    const NumberStatus status = parse_float(token, xyz[i]);
    if (status == NumberStatus::not_finite)
      p.fail("vertex coordinate '" + printable(token) + "' is not a finite number");
    if (status == NumberStatus::not_a_number) p.fail("vertex coordinate '" + printable(token) + "' is not a number");
  }
  // Extra values (w, or the r g b colour extension) must still be numbers; a '#' starts a comment.
  for (string_view token = next_token(rest); !token.empty() && token.front() != '#'; token = next_token(rest)) {
    float ignored = 0.0f;
    if (parse_float(token, ignored) == NumberStatus::not_a_number)
      p.fail("unexpected '" + printable(token) + "' after vertex coordinates");
  }
  ++p.local.vertices;
  p.check_size(1);
  if (p.context.keep) p.out.positions.emplace_back(xyz[0], xyz[1], xyz[2]);
}

/// `vn x y z`: the values are read leniently (lenient_float), since a zero or non-finite normal only falls back to
/// the geometric normal; the three tokens are required.
void parse_normal(string_view rest, ChunkParser& p) {
  const string_view x = next_token(rest), y = next_token(rest), z = next_token(rest);
  if (x.empty() || y.empty() || z.empty()) p.fail("normal needs three components");
  ++p.local.normals;
  p.check_size(1);
  if (p.context.keep) p.out.normals.emplace_back(lenient_float(x), lenient_float(y), lenient_float(z));
}

/// `vt u [v [w]]`: at least one value, read leniently (the texture lookup wraps them and reads non-finite ones
/// as 0); a missing v is 0.
void parse_texcoord(string_view rest, ChunkParser& p) {
  if (trim(rest).empty()) p.fail("texture coordinate needs a value");
  ++p.local.texcoords;
  p.check_size(1);
  if (p.context.keep) {
    const string_view u = next_token(rest), v = next_token(rest);
    p.out.texcoords.emplace_back(lenient_float(u), lenient_float(v));
  }
}

/// Checks one face/line/point vertex reference ("i", "i/j", "i//k", "i/j/k") against the counts so far and, for a
/// face, fills `corner` (a relative index the chunk cannot place yet goes to out.relative).
void parse_vertex_reference(string_view token, const char* what, ChunkParser& p, bool& has_normal, Corner* corner) {
  string_view parts[3];
  size_t part_count = 0;
  string_view rest = token;
  while (true) {
    const size_t slash = rest.find('/');
    if (part_count == 3) p.fail(std::string("bad ") + what + " vertex '" + printable(token) + "'");
    parts[part_count++] = rest.substr(0, slash);
    if (slash == string_view::npos) break;
    rest.remove_prefix(slash + 1);
  }
  struct Slot {
    const char* kind;
    const char* noun;
    uint64_t local;   ///< this chunk's count so far
    uint64_t before;  ///< the count before the chunk (0 when unknown)
  };
  const ObjCounts* before = p.context.before;
  const Slot slots[3] = {{"", "vertices", p.local.vertices, before ? before->vertices : 0},
                         {" texture", "texture coordinates", p.local.texcoords, before ? before->texcoords : 0},
                         {" normal", "normals", p.local.normals, before ? before->normals : 0}};
  uint32_t* fields[3] = {nullptr, nullptr, nullptr};
  if (corner) fields[0] = &corner->v, fields[1] = &corner->t, fields[2] = &corner->n;
  for (size_t i = 0; i < part_count; ++i) {
    // Only the texture slot of "i//k" may be empty; any other empty slot would be read as index 0.
    if (parts[i].empty() && i == 1 && part_count == 3) continue;
    long long index = 0;
    const NumberStatus status = parse_integer(parts[i], index);
    if (status == NumberStatus::not_a_number)
      p.fail(std::string("bad ") + what + " vertex '" + printable(token) + "' (not an integer index)");
    const Slot& slot = slots[i];
    const auto count = static_cast<long long>(slot.local + slot.before);
    const auto out_of_range = [&] {
      p.fail(std::string(what) + slot.kind + " index " + printable(parts[i]) + " out of range (file has " +
             std::to_string(count) + " " + slot.noun + " so far)");
    };
    if (status == NumberStatus::not_finite) out_of_range();
    if (index == 0)
      p.fail(std::string(what) + slot.kind + " index 0 in '" + printable(token) + "' (OBJ indices start at 1)");
    // |index| may reach up to the count so far; beyond the chunk's own, the chunks before must make up the rest.
    const unsigned long long magnitude =
        index > 0 ? static_cast<unsigned long long>(index) : 0ull - static_cast<unsigned long long>(index);
    if (before) {
      if (magnitude > static_cast<unsigned long long>(count)) out_of_range();
    } else if (magnitude > slot.local) {
      if (magnitude > kMaxElements) out_of_range();  // no file has that many, whatever came before
      p.out.needed_before[i] = std::max<uint64_t>(p.out.needed_before[i], magnitude - slot.local);
    }
    if (i == 2) has_normal = true;
    if (!fields[i]) continue;
    if (index > 0) {
      *fields[i] = static_cast<uint32_t>(index - 1);
    } else if (before) {
      *fields[i] = static_cast<uint32_t>(count + index);
    } else {
      // Placed by obj_read once the count before the chunk is known.
      p.out.relative.push_back({p.out.corners.size(), static_cast<uint8_t>(i),
                                static_cast<int64_t>(slot.local) + static_cast<int64_t>(index)});
    }
  }
}

/// The common reference: "i", "i/j", "i//k" or "i/j/k" with plain positive indices of at most 9 digits that are
/// in range, read without the general path's splitting. Returns false, having changed nothing, for anything else,
/// which parse_vertex_reference then reads (and refuses, naming what is wrong).
bool parse_plain_reference(string_view token, ChunkParser& p, bool& has_normal, Corner* corner) {
  uint32_t values[3] = {0, 0, 0};
  bool present[3] = {false, false, false};
  const char* c = token.data();
  const char* const end = c + token.size();
  for (size_t part = 0;; ++part) {
    if (part == 3) return false;
    const char* const digits = c;
    uint32_t value = 0;
    while (c != end && *c >= '0' && *c <= '9' && c - digits < 9) value = 10 * value + static_cast<uint32_t>(*c++ - '0');
    if (c != digits) {
      if (value == 0) return false;
      values[part] = value;
      present[part] = true;
    } else if (!(part == 1 && c != end && *c == '/')) {
      return false;  // only the texture slot of "i//k" may be empty
    }
    if (c == end) break;
    if (*c != '/') return false;
    if (++c == end) return false;
  }
  const ObjCounts* before = p.context.before;
  const uint64_t local[3] = {p.local.vertices, p.local.texcoords, p.local.normals};
  const uint64_t earlier[3] = {before ? before->vertices : 0, before ? before->texcoords : 0,
                               before ? before->normals : 0};
  for (size_t i = 0; i < 3; ++i)
    if (present[i] && values[i] > local[i] + earlier[i] && (before || values[i] > kMaxElements)) return false;
  for (size_t i = 0; i < 3; ++i) {
    if (!present[i]) continue;
    // Beyond the chunk's own, the chunks before must make up the rest (checked when they are joined).
    if (!before && values[i] > local[i])
      p.out.needed_before[i] = std::max<uint64_t>(p.out.needed_before[i], values[i] - local[i]);
  }
  has_normal = has_normal || present[2];
  if (corner) {
    uint32_t* fields[3] = {&corner->v, &corner->t, &corner->n};
    for (size_t i = 0; i < 3; ++i)
      if (present[i]) *fields[i] = values[i] - 1;
  }
  return true;
}

/// `f`, `l` or `p`: every reference in range and enough of them; a face also keeps its corners and triangles, and
/// refuses to be more ear clipping than a load should take. Lines and points draw nothing.
void parse_element(string_view keyword, string_view rest, ChunkParser& p) {
  const bool face = keyword == "f";
  const char* what = face ? "face" : keyword == "l" ? "line" : "point";
  const size_t minimum = face ? 3 : keyword == "l" ? 2 : 1;
  const bool keep = face && p.context.keep;
  size_t count = 0;
  bool has_normal = false;
  for (string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
    Corner corner;
    if (!parse_plain_reference(token, p, has_normal, keep ? &corner : nullptr))
      parse_vertex_reference(token, what, p, has_normal, keep ? &corner : nullptr);
    if (keep) p.out.corners.push_back(corner);
    ++count;
  }
  if (count < minimum)
    p.fail(std::string(what) + " has " + std::to_string(count) + " vert" + (count == 1 ? "ex" : "ices") +
           " (needs at least " + std::to_string(minimum) + ")");
  if (!face) return;
  // Ear clipping takes time growing with k^2 (polygon.h).
  if (count > 4) p.local.triangulation_work += static_cast<uint64_t>(count) * count;
  const uint64_t work = p.local.triangulation_work + (p.context.before ? p.context.before->triangulation_work : 0);
  if (work > kMaxTriangulationWork)
    p.fail("face has " + std::to_string(count) +
           " vertices: too large to triangulate in reasonable time (the squared vertex counts of "
           "large faces may add up to 4e9, one face of 63245 vertices)");
  ++p.local.faces;
  p.local.corners += count;
  p.local.triangles += count - 2;
  if (!p.local.seen_usemtl) p.out.triangles_before_usemtl += count - 2;
  p.out.references_normals = p.out.references_normals || has_normal;
  p.check_size(count - 2);
  if (p.context.keep) {
    p.out.face_sizes.push_back(static_cast<uint8_t>(std::min<size_t>(count, 255)));
    if (count >= 255) p.out.large_face_sizes.push_back(static_cast<uint32_t>(count));
  }
}

}  // namespace

bool scene_fits(const ObjCounts& s, uint64_t text_bytes, const MemoryBudget& budget) {
  return s.vertices <= kMaxElements && s.triangles <= kMaxElements &&
         scene_memory_bytes(text_bytes, s.vertices, s.normals, s.texcoords, s.triangles) <= budget.bytes;
}

void parse_chunk(string_view text, const ParseContext& context, ObjChunk& out) {
  ChunkParser p{context, out, out.counts};
  const TextScan scan = scan_text(text);
  for_each_line(
      text,
      [&](size_t line, string_view raw) {
        p.line = line;
        if (scan.binary) check_text_bytes(raw, p);
        string_view rest = trim(raw);
        if (rest.empty() || rest.front() == '#') return;
        const string_view keyword = next_token(rest);

        if (keyword == "v") {
          parse_vertex(rest, p);
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
          parse_element(keyword, rest, p);
        } else if (keyword == "vn") {
          parse_normal(rest, p);
        } else if (keyword == "vt") {
          parse_texcoord(rest, p);
        } else if (keyword == "usemtl") {
          p.local.seen_usemtl = true;
          const bool after_mtllib = p.local.seen_mtllib || (context.before && context.before->seen_mtllib);
          if (context.keep) {
            out.runs.push_back({out.counts.faces, static_cast<uint32_t>(out.usemtls.size())});
            out.usemtls.push_back({std::string(next_token(rest)), p.reported_line(), after_mtllib});
          }
        } else if (keyword == "mtllib") {
          const string_view names = trim(rest);
          if (names.empty()) {
            out.empty_mtllib_lines.push_back(p.reported_line());
          } else {
            p.local.seen_mtllib = true;
            out.mtllibs.push_back({std::string(names), p.reported_line()});
          }
        } else if (!is_known_statement(keyword)) {
          p.fail("unknown statement '" + printable(keyword) + "'");
        }
      },
      scan.carriage_return);
  out.counts.lines = p.line;
}

}  // namespace lueur::obj
