// The OBJ parser: reads the lines of one chunk of an OBJ text once, refusing with SceneError "file:line: ..." what
// would be misread (bad numbers, out-of-range indices, binary data, a scene that outgrows the memory budget), and
// keeps what the scene needs: positions, normals, texture coordinates, face corners and material switches. Chunks
// are parsed independently (obj_read.h runs them on every core and joins them in file order); what a chunk cannot
// know alone (the counts before it) is checked when they are known. Internal to src/scene; depends on core and
// obj_loader.h only.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/huge_pages.h"
#include "core/math.h"
#include "core/memory_budget.h"

namespace lueur::obj {

/// About 8 s of ear clipping on one core: the squared corner counts of a file's faces of more than 4 corners may add
/// up to this (one face of 63245 corners).
inline constexpr uint64_t kMaxTriangulationWork = 4'000'000'000;

/// Vertex and triangle indices are uint32_t (with one reserved value) in Scene.
inline constexpr uint64_t kMaxElements = 0x7fffffff;

/// One `mtllib` line.
struct MtlLib {
  std::string names;  ///< everything after `mtllib`, trimmed (one name with spaces, or several names)
  size_t line = 0;
};

/// One `usemtl` line.
struct UseMtl {
  std::string name;
  size_t line = 0;
  bool after_mtllib = false;  ///< materials are only known from mtllib lines above the usemtl
};

/// What the lines of a chunk (or of every chunk before one) add up to.
struct ObjCounts {
  uint64_t lines = 0, vertices = 0, normals = 0, texcoords = 0;
  uint64_t faces = 0, corners = 0, triangles = 0;  ///< triangles: k - 2 per face of k corners
  uint64_t triangulation_work = 0;                 ///< k^2 summed over faces with k > 4 (ear clipping)
  bool seen_usemtl = false, seen_mtllib = false;

  void add(const ObjCounts& more);
};

inline constexpr uint32_t kNoIndex = 0xffffffffu;

/// A face corner: 0-based indices into the whole file's v, vt and vn (kNoIndex where the corner has none).
struct Corner {
  uint32_t v = kNoIndex, t = kNoIndex, n = kNoIndex;
};

/// A relative (negative) index read before the chunk knew the counts before it: the corner's slot is the count
/// before the chunk plus `local` (which may be negative: a vertex of an earlier chunk).
struct RelativeIndex {
  uint64_t corner = 0;
  uint8_t slot = 0;  ///< 0: v, 1: vt, 2: vn
  int64_t local = 0;
};

/// Faces from `first_face` (of the chunk) on take the material of the chunk's usemtl line `usemtl`.
struct MaterialRun {
  uint64_t first_face = 0;
  uint32_t usemtl = 0;
};

/// What one chunk holds once parsed. Line numbers in it are the file's when the counts before it were known,
/// else the chunk's own (obj_read.cpp adds the lines before it).
struct ObjChunk {
  ObjCounts counts;
  HugePageVector<Vec3> positions;  ///< the big arrays on huge pages: fewer first-touch faults as they grow
  std::vector<Vec3> normals;  ///< as written; obj_convert normalises them
  std::vector<Vec2> texcoords;
  HugePageVector<Corner> corners;
  HugePageVector<uint8_t> face_sizes;      ///< corners per face; 255: the next entry of large_face_sizes
  std::vector<uint32_t> large_face_sizes;  ///< faces of 255 corners or more
  std::vector<RelativeIndex> relative;
  std::vector<MaterialRun> runs;
  std::vector<MtlLib> mtllibs;
  std::vector<UseMtl> usemtls;
  std::vector<size_t> empty_mtllib_lines;
  uint64_t triangles_before_usemtl = 0;  ///< triangles of faces above the chunk's first usemtl
  bool references_normals = false;
  /// The smallest counts (v, vt, vn) before the chunk that put every index it read in range.
  uint64_t needed_before[3] = {0, 0, 0};
  /// A line was refused while the counts before the chunk were unknown: obj_read parses it again with them, for
  /// the message of the line (and of any line above it).
  bool refused = false;
};

/// What parse_chunk needs besides the text.
struct ParseContext {
  const std::string& label;
  const MemoryBudget& budget;
  uint64_t text_bytes = 0;  ///< the whole file's, for the memory check
  /// The counts before the chunk: known, every check is exact and messages name the file's line; null, checks
  /// that need them become needed_before and messages name the chunk's line.
  const ObjCounts* before = nullptr;
  bool keep = true;  ///< false: only check and count (the error path's second reading)
  /// The memory every chunk's elements so far need (scene_memory_bytes without the text), summed across the
  /// threads: a chunk stops once all of them together outgrow the budget, rather than each chunk filling memory up
  /// to it. May be null.
  std::atomic<uint64_t>* memory_needed = nullptr;
};

/// Parses `text` (whole lines) into `out`. Throws SceneError "label:line: ..." at the first line refused.
void parse_chunk(std::string_view text, const ParseContext& context, ObjChunk& out);

/// Whether counts `so_far` (with `text_bytes` of text) stay within Scene's 32-bit indices and the memory budget: the
/// check every line makes, and the join makes at each chunk's end.
bool scene_fits(const ObjCounts& so_far, uint64_t text_bytes, const MemoryBudget& budget);

}  // namespace lueur::obj
