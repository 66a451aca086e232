// The conversion step of the OBJ loader: joins the parsed chunks of an OBJ text (obj_read.h) and its MTL files (read
// by tinyobjloader) into Lueur's flat Scene (positions, normals, materials, triangles, emitters, a default light
// where there is none).
// Internal to src/scene; tinyobjloader stays inside obj_convert.cpp and never leaks into this header.
// Never depends on GL, the BVH or the render passes.
#pragma once

#include <string>
#include <vector>

#include "scene/load_stages.h"
#include "scene/mtl_scan.h"
#include "scene/obj_loader.h"
#include "scene/obj_read.h"

namespace lueur::obj {

/// Builds the Scene named `scene_name` from `parsed` (its warnings move into the result, its chunks are released as
/// they are used) and `mtl_sources` (in mtllib order); messages name the OBJ as `label`. The clock is moved on to the
/// normals' stage. Throws SceneError when no triangle results, and when no default light fits in float.
LoadedScene build_scene(ParsedObj& parsed, const std::string& label, const std::string& scene_name,
                        const std::vector<MtlSource>& mtl_sources, const LoadOptions& options, StageClock& clock);

}  // namespace lueur::obj
