// Building either back-end behind the Accelerator interface.
#include "accel/accelerator.h"

namespace lueur {

Accelerator build_accelerator(const std::vector<Vec3>& corners, AccelKind kind, const HitFilter& filter) {
  Accelerator accel;
  accel.kind = kind;
  accel.filter = filter;
  if (kind == AccelKind::kEmbree)
    accel.embree = build_embree_scene(corners, filter);
  else
    accel.bvh = build_bvh(corners);
  return accel;
}

Accelerator build_accelerator(const IndexedTriangles& triangles, AccelKind kind, const HitFilter& filter,
                              const BuildProgress& progress) {
  if (kind == AccelKind::kEmbree) {
    std::vector<Vec3> corners;
    corners.reserve(3 * triangles.count);
    for (size_t i = 0; i < triangles.count; ++i)
      for (size_t k = 0; k < 3; ++k)
        corners.push_back(triangles.positions[triangles.indices[i * triangles.stride + k]]);
    return build_accelerator(corners, kind, filter);
  }
  Accelerator accel;
  accel.kind = kind;
  accel.filter = filter;
  accel.bvh = build_bvh(triangles, false, progress);
  return accel;
}

size_t accelerator_resident_bytes(const Accelerator& accel) {
  if (accel.kind == AccelKind::kEmbree) return accel.embree ? embree_resident_bytes(*accel.embree) : 0;
  return accel.bvh.resident_bytes();
}

size_t accelerator_bytes(const Accelerator& accel) {
  if (accel.kind == AccelKind::kEmbree) return accel.embree ? embree_bytes(*accel.embree) : 0;
  return accel.bvh.traversal_bytes();
}

}  // namespace lueur
