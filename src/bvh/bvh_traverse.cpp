// Queries on Lueur's BVH: the shared ray-triangle test, and the closest-hit and any-hit traversals of the 4-wide
// SSE tree (the 8-wide AVX2 tree has its own in bvh_traverse_avx.cpp). Depends on core (math, ray) and bvh.h only;
// this is the renderer's hot path, so no allocation and no virtual calls.

#include "bvh/bvh_kernels.h"

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

namespace {

template <typename Count>
Hit closest4(const Bvh& bvh, const Ray& ray, const Count& count) {
  count.query();
  if (bvh.empty()) return Hit{};
  const RayData r(ray);
  const RayLanes lanes(r);
  const BoxLanes<Sse> box_lanes(r);
  const BvhWideNode* nodes = bvh.wide_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  const ChildMemory<BvhWideNode> memory{nodes, groups};
  BestHit best{r.tmax};
  StackEntry stack[kStackSize];
  uint32_t size = 0;
  StackEntry current{0, 0, 0.0f};  // the root, an inner node

  for (;;) {
    if (current.count == 0) {
      const BvhWideNode& node = nodes[current.child];
      __m128 entry_lanes;
      count.node();
      const int mask = hit_boxes(node, box_lanes, _mm_set1_ps(best.t), entry_lanes);
      if (mask != 0) {
        alignas(16) float entry[kBvhWidth];
        _mm_store_ps(entry, entry_lanes);
        current = push_children_nearest_first<kBvhWidth>(node, mask, entry, memory, stack, size);
        continue;
      }
    } else {
      count.leaf(current.count);
      intersect_leaf_closest(groups, current.child, current.count, r, lanes, best);
    }
    // Next waiting node that can still hold a hit no farther than the best one.
    do {
      if (size == 0) return make_hit(best);
      current = stack[--size];
    } while (current.entry > best.t);
  }
}

template <typename Count>
bool any4(const Bvh& bvh, const Ray& ray, const Count& count) {
  count.query();
  if (bvh.empty()) return false;
  const RayData r(ray);
  const RayLanes lanes(r);
  const BoxLanes<Sse> box_lanes(r);
  const __m128 t_limit = _mm_set1_ps(r.tmax);
  const BvhWideNode* nodes = bvh.wide_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  // Any hit ends the query, so children are taken in slot order, with no sorting and no distances kept.
  NodeRef stack[kStackSize];
  uint32_t size = 0;
  NodeRef current{0, 0};
  for (;;) {
    if (current.count == 0) {
      const BvhWideNode& node = nodes[current.child];
      __m128 entry;
      count.node();
      const int mask = hit_boxes(node, box_lanes, t_limit, entry);
      if (mask != 0) {
        current = push_children_in_order(node, mask, stack, size);
        continue;
      }
    } else {
      count.leaf(current.count);
      if (intersect_leaf_any(groups, current.child, current.count, r, lanes)) return true;
    }
    if (size == 0) return false;
    current = stack[--size];
  }
}

}  // namespace

Hit intersect_closest(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray);
  return closest4(bvh, ray, NoCounts{});
}

bool intersect_any(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray);
  return any4(bvh, ray, NoCounts{});
}

Hit intersect_closest(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray, counts);
  return closest4(bvh, ray, Counting{counts});
}

bool intersect_any(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray, counts);
  return any4(bvh, ray, Counting{counts});
}

}  // namespace lueur
