// Splits an OBJ face into triangles: a quad along its shorter diagonal, a larger polygon by ear clipping in the
// plane it lies closest to. Depends on core only.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace lueur {

/// The triangles of a face whose corners lie at `points` (in the face's order), as corner numbers (0 to
/// points.size() - 1) appended to `out`, each wound as the face is. A triangle is kept as it is; a quad is split along
/// its shorter diagonal (the one from corner 1 to corner 3 when they tie); a larger polygon is ear-clipped: an ear
/// holds no other corner, not even on its edges or corners. Where no ear is left (a polygon that crosses or retraces
/// itself) the rest of the face is lost: fewer than points.size() - 2 triangles, which the loader reports. A polygon
/// without area is cut as a fan of zero-area triangles.
void triangulate_face(const std::vector<Vec3>& points, std::vector<std::array<uint32_t, 3>>& out);

}  // namespace lueur
