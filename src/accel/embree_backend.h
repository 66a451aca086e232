// Embree 3 as a second back-end behind Lueur's closest-hit and any-hit interface. Only embree_backend.cpp sees
// Embree's headers; a build without Embree links embree_missing.cpp instead, whose functions say it is absent.
// Depends on core (math, ray) and the BVH header (its triangle test and HitFilter).
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

#include "bvh/bvh.h"
#include "core/ray.h"

namespace lueur {

/// An accelerator that cannot be built: Embree asked for in a build without it, or an Embree error.
struct AccelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// An Embree device and committed scene plus the triangles in scene order, opaque outside embree_backend.cpp.
struct EmbreeScene;

/// True when this build links Embree.
bool embree_available();

/// Builds Embree's BVH (high build quality) over triangles given as three corners each, in input order, so that
/// Embree's primitive ids are the input indices. Triangles that build_bvh drops (non-finite vertices or edges) are
/// left out here too. When `filter` is set, Embree's intersect and occluded filter functions refuse the hits it
/// refuses, judged at the barycentrics Lueur's own triangle test gives (so both back-ends cut the same holes).
/// Throws AccelError without Embree or when Embree fails.
std::shared_ptr<const EmbreeScene> build_embree_scene(const std::vector<Vec3>& corners, const HitFilter& filter = {});

/// Closest hit through rtcIntersect1. The triangle is Embree's; t, u, v are then recomputed with Lueur's own
/// triangle test (intersect_triangle) on that triangle, so that a hit on the same triangle is the same Hit,
/// bit for bit, as Lueur's BVH reports. Where Lueur's test rejects Embree's hit (a grazing edge), Embree's
/// values are kept.
Hit embree_intersect_closest(const EmbreeScene& scene, const Ray& ray);

/// Closest hit through rtcIntersect1 with Embree's own t, u, v: what the benchmark times.
Hit embree_intersect_closest_raw(const EmbreeScene& scene, const Ray& ray);

/// Any hit through rtcOccluded1.
bool embree_intersect_any(const EmbreeScene& scene, const Ray& ray);

/// Bytes Embree allocated for the scene (its BVH and leaf primitives, through its memory monitor); the vertex and
/// index buffers it reads (shared with Lueur) and the triangles kept for the exact hit are not counted.
size_t embree_bytes(const EmbreeScene& scene);

/// Bytes an Embree user keeps in memory while rays are traced: Embree's own allocations and the vertex and index
/// buffers its triangles read (Lueur's copy of each triangle for the exact hit, which Embree does not need, is left
/// out).
size_t embree_resident_bytes(const EmbreeScene& scene);

/// The wall time of the scene's rtcCommitScene, Embree's BVH build, as its users quote it: the device, the buffers
/// and the geometry were made beforehand.
double embree_commit_seconds(const EmbreeScene& scene);

}  // namespace lueur
