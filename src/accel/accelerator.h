// The one closest-hit and any-hit interface the renderer calls, over either back-end: Lueur's own BVH or Embree.
// Depends on core, bvh and the Embree back-end's opaque handle (never on Embree's headers).
#pragma once

#include <memory>
#include <vector>

#include "accel/accel_kind.h"
#include "accel/embree_backend.h"
#include "bvh/bvh.h"

namespace lueur {

/// A built acceleration structure: the kind, and the structure of that kind.
struct Accelerator {
  AccelKind kind = AccelKind::kLueur;
  Bvh bvh;                                    ///< kind == kLueur
  std::shared_ptr<const EmbreeScene> embree;  ///< kind == kEmbree
};

/// Builds the chosen back-end over triangles given as three corners each (as build_bvh takes them); hits report
/// the input index. Throws AccelError for Embree in a build without it.
Accelerator build_accelerator(const std::vector<Vec3>& corners, AccelKind kind);

/// Bytes the structure's queries read (Lueur: wide nodes and triangle groups; Embree: what its memory monitor
/// reports).
size_t accelerator_bytes(const Accelerator& accel);

/// Closest hit with t in (ray.tmin, ray.tmax); both back-ends give the same Hit for a hit on the same triangle.
inline Hit intersect_closest(const Accelerator& accel, const Ray& ray) {
  return accel.kind == AccelKind::kEmbree ? embree_intersect_closest(*accel.embree, ray)
                                          : intersect_closest(accel.bvh, ray);
}

/// True if anything is hit with t in (ray.tmin, ray.tmax): the shadow-ray query.
inline bool intersect_any(const Accelerator& accel, const Ray& ray) {
  return accel.kind == AccelKind::kEmbree ? embree_intersect_any(*accel.embree, ray) : intersect_any(accel.bvh, ray);
}

}  // namespace lueur
