// The traversals of bvh_traversal.h on the 8-wide tree, compiled with AVX2 and called only when the CPU has AVX2
// (bvh_avx2_enabled). Triangle groups are still tested four at a time by the shared SSE kernel. Each lane of the
// 8-wide box test computes the scalar plane distances exactly and combines them conservatively (see Avx): the BVH
// stays bit-identical to the brute-force loop.
//
// Only the code below the target pragma is built for AVX2, not the whole file (no -mavx2): the headers included
// before it (the standard library, GLM, Lueur's inline helpers) keep their baseline code wherever the compiler leaves
// an out-of-line copy, and the copy the linker keeps for the whole program never holds an AVX instruction
// (tests/check_avx_objects.sh). What is built for AVX2 has internal linkage (bvh_traversal.h, Avx below).

#include <emmintrin.h>
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <limits>
#include <utility>

#include "bvh/bvh.h"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

#include "bvh/bvh_kernels.h"
#include "bvh/bvh_traversal.h"

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
  static void store(float* p, V a) { _mm256_store_ps(p, a); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static V min(V a, V b) { return as_float(_mm256_min_epi32(as_int(a), as_int(b))); }
  static V max(V a, V b) { return as_float(_mm256_max_epi32(as_int(a), as_int(b))); }
  static int less_equal_mask(V a, V b) { return _mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ)); }
};

}  // namespace

Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray) {
  return closest_hit<Avx, BvhWideNode8>(bvh, ray, NoCounts{});
}
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray) { return any_hit<Avx, BvhWideNode8>(bvh, ray, NoCounts{}); }
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  return closest_hit<Avx, BvhWideNode8>(bvh, ray, Counting{counts});
}
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray, TraversalCounts& counts) {
  return any_hit<Avx, BvhWideNode8>(bvh, ray, Counting{counts});
}
Hit intersect_closest_wide8(const Bvh& bvh, const Ray& ray, const HitFilter& filter) {
  return closest_hit<Avx, BvhWideNode8>(bvh, ray, NoCounts{}, filter);
}
bool intersect_any_wide8(const Bvh& bvh, const Ray& ray, const HitFilter& filter) {
  return any_hit<Avx, BvhWideNode8>(bvh, ray, NoCounts{}, filter);
}

}  // namespace lueur

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
