// The traversals of the 8-wide tree, compiled with AVX2 (this file only; see CMakeLists.txt) and called only when
// the CPU has AVX2 (bvh_avx2_enabled). Triangle groups are still tested four at a time by the shared SSE kernel.
// Each lane of the 8-wide box test computes the scalar plane distances exactly and combines them conservatively
// (see Avx): the BVH stays bit-identical to the brute-force loop.

#include <immintrin.h>

#include "bvh/bvh_kernels.h"

namespace lueur {
namespace {

/// The AVX2 operations of the 8-wide box test. min and max compare the floats' bit patterns as signed integers: one
/// cycle of latency instead of four on the node test's critical path. That order is the floats' unless both are
/// negative (-0 included), where it is reversed; so the integer max of some numbers is never above their float max,
/// and the integer min never below their float min. A box's span comes out the same or wider (only where every
/// entry candidate, or the exit, is negative), and entry distances are never larger: the test stays conservative,
/// and the hits reported stay exactly the brute-force loop's.
struct Avx {
  using V = __m256;
  static constexpr uint32_t kWidth = kBvhWidth8;
  static __m256i as_int(V a) { return _mm256_castps_si256(a); }
  static V as_float(__m256i a) { return _mm256_castsi256_ps(a); }
  static V broadcast(float x) { return _mm256_set1_ps(x); }
  static V load(const float* p) { return _mm256_load_ps(p); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static V min(V a, V b) { return as_float(_mm256_min_epi32(as_int(a), as_int(b))); }
  static V max(V a, V b) { return as_float(_mm256_max_epi32(as_int(a), as_int(b))); }
  static int less_equal_mask(V a, V b) { return _mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ)); }
};

constexpr uint32_t kStackSize8 = (kBvhWidth8 - 1) * kBvhMaxDepth + 1;

template <typename Count>
Hit closest8(const Bvh& bvh, const Ray& ray, const Count& count) {
  count.query();
  if (bvh.empty()) return Hit{};
  const RayData r(ray);
  const RayLanes lanes(r);
  const BoxLanes<Avx> box_lanes(r);
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
      count.node();
      const int mask = hit_boxes(node, box_lanes, _mm256_set1_ps(best.t), entry_lanes);
      if (mask != 0) {
        alignas(32) float entry[kBvhWidth8];
        _mm256_store_ps(entry, entry_lanes);
        current = push_children_nearest_first<kBvhWidth8>(node, mask, entry, memory, stack, size);
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
bool any8(const Bvh& bvh, const Ray& ray, const Count& count) {
  count.query();
  if (bvh.empty()) return false;
  const RayData r(ray);
  const RayLanes lanes(r);
  const BoxLanes<Avx> box_lanes(r);
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

Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray) { return closest8(bvh, ray, NoCounts{}); }
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray) { return any8(bvh, ray, NoCounts{}); }
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  return closest8(bvh, ray, Counting{counts});
}
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  return any8(bvh, ray, Counting{counts});
}

}  // namespace lueur
