// Writes a Scene back out as OBJ + MTL (scene export and loader round-trip tests).
// Depends on core and scene only; never on tinyobjloader, GL or the render passes.
#pragma once

#include "scene/scene.h"

#include <string>

namespace lueur {

/// Writes `obj_path` and, beside it with the same stem, its MTL file (referenced by an `mtllib` line), each
/// atomically (write_file_atomically; throws IoError). Positions use "%.9g" so that every float reads back
/// bit-exactly, and so do the shading normals (vn) and texture coordinates (vt), given on a face where all three
/// of its corners have one. All materials are written, in order, with Kd Ks Ns Ke and their map_Kd / map_d names
/// as the scene's MTL gave them (relative to its folder); names that OBJ cannot carry (empty, blanks, duplicates)
/// are made usable and unique. Loading the result with load_obj gives back the same positions, normals, texture
/// coordinates, triangles and materials for any scene whose material names are already usable and unique.
void write_obj(const Scene& scene, const std::string& obj_path);

}  // namespace lueur
