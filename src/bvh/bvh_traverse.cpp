// Queries on Lueur's BVH: the shared ray-triangle test, and the closest-hit and any-hit queries, which run the
// traversals of bvh_traversal.h on the 4-wide SSE tree here and hand the 8-wide AVX2 tree to bvh_traverse_avx.cpp.
// Depends on core (math, ray) and bvh.h only; this is the renderer's hot path, so no allocation and no virtual
// calls.

#include "bvh/bvh_traversal.h"

namespace lueur {

Box3 bvh_triangle_box(const BvhTriangle& tri) { return triangle_box(tri.v0, tri.e1, tri.e2); }

bool intersect_triangle(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t, float& u, float& v) {
  float tt, uu, vv;
  if (!moller_trumbore(ray.origin, ray.dir, v0, e1, e2, tt, uu, vv)) return false;
  if (!(tt > ray.tmin && tt < ray.tmax)) return false;
  // The inverse only after a candidate hit: the brute-force loop then costs little more than Möller–Trumbore.
  if (!clamp_to_triangle_box(SlabRay(ray.origin, safe_inverse(ray.dir)), v0, e1, e2, tt)) return false;
  if (!(tt > ray.tmin && tt < ray.tmax)) return false;
  t = tt;
  u = uu;
  v = vv;
  return true;
}

Hit intersect_closest(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray);
  return closest_hit<Sse, BvhWideNode>(bvh, ray, NoCounts{});
}

bool intersect_any(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray);
  return any_hit<Sse, BvhWideNode>(bvh, ray, NoCounts{});
}

Hit intersect_closest(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray, counts);
  return closest_hit<Sse, BvhWideNode>(bvh, ray, Counting{counts});
}

bool intersect_any(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray, counts);
  return any_hit<Sse, BvhWideNode>(bvh, ray, Counting{counts});
}

Hit intersect_closest(const Bvh& bvh, const Ray& ray, const HitFilter& filter) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray, filter);
  return closest_hit<Sse, BvhWideNode>(bvh, ray, NoCounts{}, filter);
}

bool intersect_any(const Bvh& bvh, const Ray& ray, const HitFilter& filter) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray, filter);
  return any_hit<Sse, BvhWideNode>(bvh, ray, NoCounts{}, filter);
}

}  // namespace lueur
