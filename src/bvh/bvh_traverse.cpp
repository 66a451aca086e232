// Queries on Lueur's BVH: the shared ray-triangle test, and the closest-hit and any-hit traversals of the 4-wide
// SSE tree (the 8-wide AVX tree has its own in bvh_traverse_avx.cpp). Depends on core (math, ray) and bvh.h only;
// this is the renderer's hot path, so no allocation and no virtual calls.

#include "bvh/bvh_kernels.h"

namespace lueur {

Box3 bvh_triangle_box(const BvhTriangle& tri) { return triangle_box(tri.v0, tri.e1, tri.e2); }

bool intersect_triangle(const Ray& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t, float& u, float& v) {
  float tt, uu, vv;
  if (!moller_trumbore(ray.origin, ray.dir, v0, e1, e2, tt, uu, vv)) return false;
  // The inverse only after a candidate hit: the brute-force loop then costs little more than Möller–Trumbore.
  if (!clamp_to_triangle_box(ray.origin, safe_inverse(ray.dir), v0, e1, e2, tt)) return false;
  if (!(tt > ray.tmin && tt < ray.tmax)) return false;
  t = tt;
  u = uu;
  v = vv;
  return true;
}

Hit intersect_closest(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_closest_wide8(bvh, ray);
  Hit hit;
  if (bvh.empty()) return hit;
  const RayData r(ray);
  const RayLanes lanes(r);
  const BvhWideNode* nodes = bvh.wide_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  float best_t = r.tmax;
  uint32_t best_id = kNoHit;
  float best_u = 0.0f, best_v = 0.0f;

  StackEntry stack[kStackSize];
  uint32_t size = 0;
  StackEntry current{0, 0, 0.0f};  // the root, an inner node

  for (;;) {
    if (current.count == 0) {
      const BvhWideNode& node = nodes[current.child];
      __m128 entry_lanes;
      int mask = hit_boxes(node, lanes, _mm_set1_ps(best_t), entry_lanes);
      if (mask != 0) {
        alignas(16) float entry[4];
        _mm_store_ps(entry, entry_lanes);
        // The children hit, nearest first (insertion sort of at most four), so that hits in the nearer ones
        // shrink best_t and let the farther ones be dropped.
        StackEntry hits[kBvhWidth];
        uint32_t n = 0;
        while (mask != 0) {
          const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
          mask &= mask - 1;
          StackEntry e{node.child[k], node.count[k], entry[k]};
          uint32_t j = n++;
          for (; j > 0 && hits[j - 1].entry > e.entry; --j) hits[j] = hits[j - 1];
          hits[j] = e;
        }
        for (uint32_t j = n - 1; j > 0; --j) stack[size++] = hits[j];
        current = hits[0];
        continue;
      }
    } else {
      for (uint32_t g = 0; g < current.count; ++g) {
        const BvhTriangleGroup& group = groups[current.child + g];
        __m128 t4, u4, v4;
        int mask = moller_trumbore4(group, lanes, t4, u4, v4);
        while (mask != 0) {
          const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
          mask &= mask - 1;
          float t = lane(t4, k);
          if (!finish_lane(r, group, k, t)) continue;
          // Equal distances go to the lowest input index, whichever leaf was reached first.
          const uint32_t id = group.id[k];
          if (t < best_t || (t == best_t && id < best_id)) {
            best_t = t;
            best_id = id;
            best_u = lane(u4, k);
            best_v = lane(v4, k);
          }
        }
      }
    }
    // Next waiting node that can still hold a hit no farther than the best one.
    do {
      if (size == 0) {
        if (best_id != kNoHit) {
          hit.t = best_t;
          hit.triangle = best_id;
          hit.u = best_u;
          hit.v = best_v;
        }
        return hit;
      }
      current = stack[--size];
    } while (current.entry > best_t);
  }
}

bool intersect_any(const Bvh& bvh, const Ray& ray) {
  if (!bvh.wide8_nodes.empty()) return intersect_any_wide8(bvh, ray);
  if (bvh.empty()) return false;
  const RayData r(ray);
  const RayLanes lanes(r);
  const __m128 t_limit = _mm_set1_ps(r.tmax);
  const BvhWideNode* nodes = bvh.wide_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  // Any hit ends the query, so children are taken in slot order, with no sorting and no distances kept.
  struct Ref {
    uint32_t child, count;
  };
  Ref stack[kStackSize];
  uint32_t size = 0;
  Ref current{0, 0};
  for (;;) {
    if (current.count == 0) {
      const BvhWideNode& node = nodes[current.child];
      __m128 entry;
      int mask = hit_boxes(node, lanes, t_limit, entry);
      if (mask != 0) {
        auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
        mask &= mask - 1;
        current = {node.child[k], node.count[k]};
        while (mask != 0) {
          k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
          mask &= mask - 1;
          stack[size++] = {node.child[k], node.count[k]};
        }
        continue;
      }
    } else {
      for (uint32_t g = 0; g < current.count; ++g) {
        const BvhTriangleGroup& group = groups[current.child + g];
        __m128 t4, u4, v4;
        int mask = moller_trumbore4(group, lanes, t4, u4, v4);
        while (mask != 0) {
          const auto k = static_cast<uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
          mask &= mask - 1;
          float t = lane(t4, k);
          if (finish_lane(r, group, k, t)) return true;
        }
      }
    }
    if (size == 0) return false;
    current = stack[--size];
  }
}

}  // namespace lueur
