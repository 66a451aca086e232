// The OBJ validator: reads every line of an OBJ text before tinyobjloader sees it and throws SceneError
// "file:line: ..." for what tinyobjloader would silently misread (bad numbers read as 0, out-of-range indices read as
// memory), for binary data, and for a scene that outgrows the memory budget. It also summarises the file for the
// later steps. Internal to src/scene; depends on core and obj_loader.h only, never on tinyobjloader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/memory_budget.h"

namespace lueur::obj {

/// One `mtllib` line.
struct MtlLib {
  std::string names;  ///< everything after `mtllib`, trimmed (one name with spaces, or several names)
  size_t line = 0;
};

/// One `usemtl` line.
struct UseMtl {
  std::string name;
  size_t line = 0;
  bool after_mtllib = false;  ///< tinyobjloader only knows materials from mtllib lines above the usemtl
};

/// What the validator learnt on its way through the file.
struct ObjSummary {
  size_t vertices = 0, normals = 0, texcoords = 0;
  size_t expected_triangles = 0;       ///< k - 2 per face with k vertices
  uint64_t triangulation_work = 0;     ///< k^2 summed over faces with k > 4 (tinyobjloader's ear clipping)
  size_t triangles_before_usemtl = 0;  ///< faces that tinyobjloader gives material -1
  bool references_normals = false;
  std::vector<MtlLib> mtllibs;
  std::vector<UseMtl> usemtls;
  std::vector<std::string> warnings;
};

/// Checks every line of `text` (reported as `label`) and summarises it; throws SceneError at the first bad line,
/// or at the line where the counts so far need more memory than `budget`.
ObjSummary validate_obj(std::string_view text, const std::string& label, const MemoryBudget& budget);

}  // namespace lueur::obj
