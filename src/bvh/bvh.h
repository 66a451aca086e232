// Lueur's own bounding volume hierarchy: a binned-SAH BVH2 over triangles with closest-hit and any-hit queries.
// Depends on core only; knows triangles by their three vertex positions.
#pragma once

#include "core/ray.h"

#include <vector>

namespace lueur {

/// 32 bytes: the box, and either the index of the first of two adjacent children (count == 0)
/// or the first triangle of a leaf (count > 0) in the BVH's own triangle order.
struct BvhNode {
  Vec3 lo;
  uint32_t first;
  Vec3 hi;
  uint32_t count;
};

/// A triangle prepared for intersection: v0 and the two edges, stored in BVH order.
struct BvhTriangle {
  Vec3 v0, e1, e2;
  uint32_t id;  ///< index of the triangle in the input (scene) order
};

struct Bvh {
  std::vector<BvhNode> nodes;          ///< nodes[0] is the root
  std::vector<BvhTriangle> triangles;  ///< reordered once after the build so leaves read them directly
  bool empty() const { return triangles.empty(); }
};

/// Builds the hierarchy over triangles given as three vertex positions each (`corners.size() == 3 * count`).
/// Degenerate triangles are kept (they can never be hit); non-finite ones are dropped.
Bvh build_bvh(const std::vector<Vec3>& corners);

/// Closest intersection with t in (ray.tmin, ray.tmax). Ties in t go to the lowest input index, so the answer
/// does not depend on the traversal order.
Hit intersect_closest(const Bvh& bvh, const Ray& ray);

/// True if any triangle is hit with t in (ray.tmin, ray.tmax): the shadow-ray query.
bool intersect_any(const Bvh& bvh, const Ray& ray);

/// Ray-triangle test shared by the BVH and the brute-force reference; on a hit inside (tmin, tmax) writes t, u, v.
bool intersect_triangle(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t, float& u,
                        float& v);

}  // namespace lueur
