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
  HitFilter filter;  ///< set (accepts != nullptr) when some surfaces have holes: hits it refuses are passed through
};

/// Builds the chosen back-end over triangles given as three corners each (as build_bvh takes them); hits report
/// the input index. Both back-ends then count only the hits `filter` accepts, when it is set (Embree through its
/// filter functions). Throws AccelError for Embree in a build without it.
Accelerator build_accelerator(const std::vector<Vec3>& corners, AccelKind kind, const HitFilter& filter = {});

/// The same over indexed triangles, read where they are; Lueur's BVH keeps only what its queries read (the lean
/// build of build_bvh), Embree is given their corners.
/// `progress` is told Lueur's build's share done.
Accelerator build_accelerator(const IndexedTriangles& triangles, AccelKind kind, const HitFilter& filter = {},
                              const BuildProgress& progress = {});

/// Bytes the structure's queries read (Lueur: wide nodes and triangle groups; Embree: what its memory monitor
/// reports).
size_t accelerator_bytes(const Accelerator& accel);

/// Bytes the structure keeps in memory while rays are traced (Bvh::resident_bytes, embree_resident_bytes).
size_t accelerator_resident_bytes(const Accelerator& accel);

/// Closest hit with t in (ray.tmin, ray.tmax); both back-ends give the same Hit for a hit on the same triangle.
inline Hit intersect_closest(const Accelerator& accel, const Ray& ray) {
  if (accel.kind == AccelKind::kEmbree) return embree_intersect_closest(*accel.embree, ray);
  return accel.filter.accepts ? intersect_closest(accel.bvh, ray, accel.filter) : intersect_closest(accel.bvh, ray);
}

/// True if anything is hit with t in (ray.tmin, ray.tmax): the shadow-ray query.
inline bool intersect_any(const Accelerator& accel, const Ray& ray) {
  if (accel.kind == AccelKind::kEmbree) return embree_intersect_any(*accel.embree, ray);
  return accel.filter.accepts ? intersect_any(accel.bvh, ray, accel.filter) : intersect_any(accel.bvh, ray);
}

}  // namespace lueur
