// Lueur's own bounding volume hierarchy: a binned-SAH BVH2 over triangles with closest-hit and any-hit queries.
// Depends on core only; knows triangles by their three vertex positions.
#pragma once

#include "core/ray.h"

#include <vector>

namespace lueur {

/// Largest number of triangles in one leaf.
inline constexpr uint32_t kBvhMaxLeafSize = 8;
/// Bound on the depth of any node (the root has depth 0); traversal stacks of this many entries cannot overflow.
inline constexpr uint32_t kBvhMaxDepth = 128;

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

/// Prepares triangle (a, b, c) for intersection: v0 = a, e1 = b - a, e2 = c - a. A zero-area triangle (edge cross
/// product exactly zero: repeated or collinear vertices) gets zero edges, so its determinant is exactly 0 for every
/// ray and it can never be hit, whatever the rounding of the determinant would otherwise have been.
BvhTriangle make_bvh_triangle(const Vec3& a, const Vec3& b, const Vec3& c, uint32_t id);

/// The box that bounds where a hit on `tri` may lie: its vertices as the intersection test sees them (v0, v0 + e1,
/// v0 + e2), widened by a few ulps. Every node box of a BVH contains the boxes of its triangles exactly.
Box3 bvh_triangle_box(const BvhTriangle& tri);

/// Builds the hierarchy over triangles given as three vertex positions each (`corners.size() == 3 * count`).
/// Degenerate triangles are kept (they can never be hit); non-finite ones (a non-finite vertex, or edges that
/// overflow) are dropped.
Bvh build_bvh(const std::vector<Vec3>& corners);

/// Closest intersection with t in (ray.tmin, ray.tmax). Ties in t go to the lowest input index, so the answer
/// does not depend on the traversal order.
Hit intersect_closest(const Bvh& bvh, const Ray& ray);

/// True if any triangle is hit with t in (ray.tmin, ray.tmax): the shadow-ray query.
bool intersect_any(const Bvh& bvh, const Ray& ray);

/// Ray-triangle test shared by the BVH and the brute-force reference; on a hit inside (tmin, tmax) writes t, u, v.
/// Möller–Trumbore, where a zero or non-finite determinant is never a hit; its t is then clamped to the span of the
/// ray inside bvh_triangle_box (no span: no hit). Near-degenerate triangles and grazing rays can give a Möller–
/// Trumbore t far from the triangle; the clamp keeps every hit inside the node boxes above it, so the BVH queries
/// report exactly what a loop over all triangles with this function reports, bit for bit.
bool intersect_triangle(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t, float& u, float& v);

}  // namespace lueur
