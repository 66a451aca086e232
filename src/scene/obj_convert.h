// The conversion step of the OBJ loader: parses validated OBJ text and its MTL files with tinyobjloader and builds
// Lueur's flat Scene (positions, normals, materials, triangles, emitters, a default light where there is none).
// Internal to src/scene; tinyobjloader stays inside obj_convert.cpp and never leaks into this header.
// Never depends on GL, the BVH or the render passes.
#pragma once

#include <string>
#include <vector>

#include "scene/mtl_scan.h"
#include "scene/obj_loader.h"
#include "scene/obj_validate.h"

namespace lueur::obj {

/// Parses `obj_text` (already passed by validate_obj, which filled `summary`; its warnings move into the result)
/// and `mtl_sources` (in mtllib order), and builds the Scene named `scene_name`. Messages name the OBJ as `label`.
/// Throws SceneError when tinyobjloader fails, when no triangle results, and when no default light fits in float.
LoadedScene build_scene(const std::string& obj_text, const std::string& label, const std::string& scene_name,
                        ObjSummary& summary, const std::vector<MtlSource>& mtl_sources, const LoadOptions& options);

}  // namespace lueur::obj
