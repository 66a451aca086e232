// The traversals of the 8-wide tree, compiled with AVX (this file only; see CMakeLists.txt) and called only when
// the CPU has AVX (bvh_avx_enabled). Triangle groups are still tested four at a time by the shared SSE kernel.
// Each lane of the 8-wide box test repeats the scalar arithmetic exactly, like the 4-wide one: the BVH stays
// bit-identical to the brute-force loop.

#include <immintrin.h>

#include "bvh/bvh_kernels.h"

namespace lueur {
namespace {

/// The ray's origin and inverse directions, broadcast to eight lanes, and where its near and far planes lie.
struct RayLanes8 {
  __m256 ox, oy, oz, ix, iy, iz, ex, ey, ez, tmin;
  PlaneOffsets<kBvhWidth8> planes;
  explicit RayLanes8(const RayData& r)
      : ox(_mm256_set1_ps(r.origin.x)),
        oy(_mm256_set1_ps(r.origin.y)),
        oz(_mm256_set1_ps(r.origin.z)),
        ix(_mm256_set1_ps(r.slab.inv_dir.x)),
        iy(_mm256_set1_ps(r.slab.inv_dir.y)),
        iz(_mm256_set1_ps(r.slab.inv_dir.z)),
        ex(_mm256_set1_ps(r.slab.inv_dir_exit.x)),
        ey(_mm256_set1_ps(r.slab.inv_dir_exit.y)),
        ez(_mm256_set1_ps(r.slab.inv_dir_exit.z)),
        tmin(_mm256_set1_ps(r.tmin)),
        planes(r.slab.inv_dir) {}
};

/// hit_boxes on the eight children of a node (AVX min/max return their second operand on NaN, like SSE's).
inline int hit_boxes8(const BvhWideNode8& node, const RayLanes8& r, __m256 t_limit, __m256& entry) {
  const PlaneOffsets<kBvhWidth8>& p = r.planes;
  const __m256 tx0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.near[0])), r.ox), r.ix);
  const __m256 ty0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.near[1])), r.oy), r.iy);
  const __m256 tz0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.near[2])), r.oz), r.iz);
  const __m256 tx1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.far[0])), r.ox), r.ex);
  const __m256 ty1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.far[1])), r.oy), r.ey);
  const __m256 tz1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane_row(node, p.far[2])), r.oz), r.ez);
  entry = _mm256_max_ps(_mm256_max_ps(tx0, ty0), _mm256_max_ps(r.tmin, tz0));
  const __m256 exit = _mm256_min_ps(_mm256_min_ps(tx1, ty1), _mm256_min_ps(tz1, t_limit));
  return _mm256_movemask_ps(_mm256_cmp_ps(entry, exit, _CMP_LE_OQ));
}

constexpr uint32_t kStackSize8 = (kBvhWidth8 - 1) * kBvhMaxDepth + 1;

}  // namespace

Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray) {
  if (bvh.empty()) return Hit{};
  const RayData r(ray);
  const RayLanes lanes(r);
  const RayLanes8 lanes8(r);
  const BvhWideNode8* nodes = bvh.wide8_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  const ChildMemory<BvhWideNode8> memory{nodes, groups};
  BestHit best{r.tmax};
  StackEntry stack[kStackSize8];
  uint32_t size = 0;
  StackEntry current{0, 0, 0.0f};  // the root, an inner node

  for (;;) {
    if (current.count == 0) {
      const BvhWideNode8& node = nodes[current.child];
      __m256 entry_lanes;
      const int mask = hit_boxes8(node, lanes8, _mm256_set1_ps(best.t), entry_lanes);
      if (mask != 0) {
        alignas(32) float entry[kBvhWidth8];
        _mm256_store_ps(entry, entry_lanes);
        current = push_children_nearest_first<kBvhWidth8>(node, mask, entry, memory, stack, size);
        continue;
      }
    } else {
      intersect_leaf_closest(groups, current.child, current.count, r, lanes, best);
    }
    // Next waiting node that can still hold a hit no farther than the best one.
    do {
      if (size == 0) return make_hit(best);
      current = stack[--size];
    } while (current.entry > best.t);
  }
}

bool intersect_any_wide8(const Bvh& bvh, const Ray& ray) {
  if (bvh.empty()) return false;
  const RayData r(ray);
  const RayLanes lanes(r);
  const RayLanes8 lanes8(r);
  const __m256 t_limit = _mm256_set1_ps(r.tmax);
  const BvhWideNode8* nodes = bvh.wide8_nodes.data();
  const BvhTriangleGroup* groups = bvh.groups.data();

  // Any hit ends the query, so children are taken in slot order, with no sorting and no distances kept.
  NodeRef stack[kStackSize8];
  uint32_t size = 0;
  NodeRef current{0, 0};
  for (;;) {
    if (current.count == 0) {
      const BvhWideNode8& node = nodes[current.child];
      __m256 entry;
      const int mask = hit_boxes8(node, lanes8, t_limit, entry);
      if (mask != 0) {
        current = push_children_in_order(node, mask, stack, size);
        continue;
      }
    } else if (intersect_leaf_any(groups, current.child, current.count, r, lanes)) {
      return true;
    }
    if (size == 0) return false;
    current = stack[--size];
  }
}

}  // namespace lueur
