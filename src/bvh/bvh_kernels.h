// The ray-triangle and ray-box kernels of Lueur's BVH: the scalar reference test, its 4-lane SSE form, and the box
// test of a wide node's children for both tree widths (bvh_traversal.h builds the traversals on them). Internal to
// src/bvh: everything has internal linkage, because the AVX2 translation unit compiles the same functions with other
// instruction-set flags and the two copies must never be merged by the linker.
#pragma once

#include <emmintrin.h>  // SSE2 only: x86-64's baseline, so Debug builds without -march compile it too

#include <algorithm>
#include <limits>

#include "bvh/bvh.h"

namespace lueur {
namespace {

// Direction components smaller than this are replaced by it (keeping the sign) before inverting, so the slab test
// never computes 0 * inf = NaN. A ray parallel to a slab then gets a finite span along that axis (about 1e30 times
// its distance to the slab), which only matters for hits farther away than that.
constexpr float kTinyDirection = 1e-30f;
// Box exits are scaled up by a few ulps so that rounding in the slab test cannot reject a box the ray touches.
constexpr float kExitScale = 1.0f + 4.0f * std::numeric_limits<float>::epsilon();

// Hits are only reported inside a box around the triangle a few ulps wider than its vertices, so that rays grazing
// a shared edge see the same candidates as without the box.
constexpr float kTrianglePadding = 4.0f * std::numeric_limits<float>::epsilon();

// Compile to minss/maxss; no NaN reaches them (safe inverse directions, finite boxes) except a NaN t, handled below.
inline float min_f(float a, float b) { return a < b ? a : b; }
inline float max_f(float a, float b) { return a > b ? a : b; }

inline float safe_inverse(float d) {
  return 1.0f / (std::fabs(d) < kTinyDirection ? std::copysign(kTinyDirection, d) : d);
}

inline Vec3 safe_inverse(const Vec3& d) { return Vec3(safe_inverse(d.x), safe_inverse(d.y), safe_inverse(d.z)); }

/// The ray as the slab test sees it, computed once per query: the origin, the inverse direction, and that inverse
/// scaled by kExitScale for the exit planes (folding the scale into the ray keeps a multiply off every box test).
struct SlabRay {
  Vec3 origin;
  Vec3 inv_dir;
  Vec3 inv_dir_exit;
  explicit SlabRay(const Vec3& o, const Vec3& inv) : origin(o), inv_dir(inv), inv_dir_exit(inv * kExitScale) {}
};

/// The plane of a slab the ray crosses first: lo where the direction is positive (its inverse is never zero).
inline float near_plane(float lo, float hi, float inv) { return inv < 0.0f ? hi : lo; }
inline float far_plane(float lo, float hi, float inv) { return inv < 0.0f ? lo : hi; }

/// Slab test: the span [entry, exit] of the ray's line inside the box, not yet limited to the ray's interval.
/// Choosing each axis's near plane by the sign of the direction gives exactly min(t_lo, t_hi) (rounding is
/// monotone), so the SIMD kernels, which choose the planes once per ray, compute the same values bit for bit. Each
/// bound is monotone in the box, so a box inside another gets a span inside the other's: the BVH's exact agreement
/// with the brute-force loop rests on the node test and the triangle clamp both using this arithmetic.
inline void slab_span(const Vec3& lo, const Vec3& hi, const SlabRay& r, float& entry, float& exit) {
  const float tx0 = (near_plane(lo.x, hi.x, r.inv_dir.x) - r.origin.x) * r.inv_dir.x;
  const float ty0 = (near_plane(lo.y, hi.y, r.inv_dir.y) - r.origin.y) * r.inv_dir.y;
  const float tz0 = (near_plane(lo.z, hi.z, r.inv_dir.z) - r.origin.z) * r.inv_dir.z;
  const float tx1 = (far_plane(lo.x, hi.x, r.inv_dir.x) - r.origin.x) * r.inv_dir_exit.x;
  const float ty1 = (far_plane(lo.y, hi.y, r.inv_dir.y) - r.origin.y) * r.inv_dir_exit.y;
  const float tz1 = (far_plane(lo.z, hi.z, r.inv_dir.z) - r.origin.z) * r.inv_dir_exit.z;
  entry = max_f(max_f(tx0, ty0), tz0);
  exit = min_f(min_f(tx1, ty1), tz1);
}

/// What every box test of one ray needs, computed once per query.
struct RayData {
  Vec3 origin;
  Vec3 dir;
  SlabRay slab;
  float tmin;
  float tmax;
  explicit RayData(const Ray& ray)
      : origin(ray.origin), dir(ray.dir), slab(ray.origin, safe_inverse(ray.dir)), tmin(ray.tmin), tmax(ray.tmax) {}
};

inline Box3 triangle_box(const Vec3& v0, const Vec3& e1, const Vec3& e2) {
  const Vec3 v1 = v0 + e1;
  const Vec3 v2 = v0 + e2;
  const Vec3 lo = glm::min(glm::min(v0, v1), v2);
  const Vec3 hi = glm::max(glm::max(v0, v1), v2);
  const Vec3 pad(kTrianglePadding * std::max(max_abs_component(lo), max_abs_component(hi)));
  Box3 box;
  box.lo = lo - pad;
  box.hi = hi + pad;
  return box;
}

// Determinants smaller than the smallest normal float (zero included: a ray parallel to the plane, or a triangle of
// no area) are never a hit: their inverse could overflow.
constexpr float kMinDeterminant = std::numeric_limits<float>::min();

/// Möller–Trumbore without the range test on t. The inside test compares the undivided barycentric numerators
/// with the determinant, its sign folded into them (an exact sign flip), so no division is made before the ray is
/// known to cross the triangle.
inline bool moller_trumbore(const Vec3& origin, const Vec3& dir, const Vec3& v0, const Vec3& e1, const Vec3& e2,
                            float& t, float& u, float& v) {
  const Vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  const Vec3 s = origin - v0;
  const float u_num = glm::dot(s, p);
  const Vec3 q = glm::cross(s, e1);
  const float v_num = glm::dot(dir, q);
  const float abs_det = std::fabs(det);
  const float sign = det < 0.0f ? -1.0f : 1.0f;
  const float u_signed = u_num * sign, v_signed = v_num * sign;
  // Non-finite determinants come from overflowing edges; NaN numerators fail every comparison.
  if (!(abs_det >= kMinDeterminant && abs_det < kInfinity)) return false;
  if (!(u_signed >= 0.0f && v_signed >= 0.0f && u_signed + v_signed <= abs_det)) return false;
  const float inv_det = 1.0f / det;
  u = u_num * inv_det;
  v = v_num * inv_det;
  t = glm::dot(e2, q) * inv_det;
  return true;
}

/// Moves a Möller–Trumbore t into the ray's span inside the triangle's box. Only runs on the rare candidate hits.
/// The t of an ill-conditioned determinant (slivers, grazing rays) can land far from the triangle; the true hit
/// lies inside the box, so the clamp only ever brings t closer to it.
inline bool clamp_to_triangle_box(const SlabRay& ray, const Vec3& v0, const Vec3& e1, const Vec3& e2, float& t) {
  const Box3 box = triangle_box(v0, e1, e2);
  float entry, exit;
  slab_span(box.lo, box.hi, ray, entry, exit);
  if (!(entry <= exit)) return false;
  t = min_f(max_f(t, entry), exit);  // a NaN t becomes `entry`
  return true;
}

// ---- the 4-wide kernels -----------------------------------------------------------------------------------------
// Each lane computes exactly what the scalar functions above compute, operation for operation (SSE min/max return
// their second operand on NaN, like min_f/max_f; no FMA is involved), so the BVH stays bit-identical to the
// brute-force loop over intersect_triangle.

/// Where in a wide node of `Width` children (lo[3][Width] then hi[3][Width]) the near and far planes of each axis
/// lie for this ray: the lower bounds where the direction is positive.
template <uint32_t Width>
struct PlaneOffsets {
  uint32_t near[3], far[3];
  explicit PlaneOffsets(const Vec3& inv_dir) {
    constexpr uint32_t kRow = Width * sizeof(float), kHi = 3 * kRow;
    for (int axis = 0; axis < 3; ++axis) {
      const bool negative = inv_dir[axis] < 0.0f;
      near[axis] = static_cast<uint32_t>(axis) * kRow + (negative ? kHi : 0);
      far[axis] = static_cast<uint32_t>(axis) * kRow + (negative ? 0 : kHi);
    }
  }
};

/// Row `offset` bytes into a node: one of its six planes for all children.
template <typename Node>
inline const float* plane_row(const Node& node, uint32_t offset) {
  return reinterpret_cast<const float*>(reinterpret_cast<const char*>(&node) + offset);
}

/// What the 4-lane triangle test needs of the ray, broadcast: origin, direction and interval.
struct RayLanes {
  __m128 ox, oy, oz, dx, dy, dz, tmin, tmax;
  explicit RayLanes(const RayData& r)
      : ox(_mm_set1_ps(r.origin.x)),
        oy(_mm_set1_ps(r.origin.y)),
        oz(_mm_set1_ps(r.origin.z)),
        dx(_mm_set1_ps(r.dir.x)),
        dy(_mm_set1_ps(r.dir.y)),
        dz(_mm_set1_ps(r.dir.z)),
        tmin(_mm_set1_ps(r.tmin)),
        tmax(_mm_set1_ps(r.tmax)) {}
};

/// The SSE operations the 4-wide box test runs on; the 8-wide traversal supplies the same for AVX2 (Avx, in its own
/// translation unit, compiled with -mavx2), so that one box test serves both widths.
struct Sse {
  using V = __m128;
  static constexpr uint32_t kWidth = kBvhWidth;
  static V broadcast(float x) { return _mm_set1_ps(x); }
  static V load(const float* p) { return _mm_load_ps(p); }
  static void store(float* p, V a) { _mm_store_ps(p, a); }
  static V sub(V a, V b) { return _mm_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm_mul_ps(a, b); }
  static V min(V a, V b) { return _mm_min_ps(a, b); }
  static V max(V a, V b) { return _mm_max_ps(a, b); }
  static int less_equal_mask(V a, V b) { return _mm_movemask_ps(_mm_cmple_ps(a, b)); }
};

/// What the box test needs of the ray, broadcast to the lanes of `Simd::V`: origin and inverse directions, and
/// where the near and far planes of a node of `Simd::kWidth` children lie.
template <typename Simd>
struct BoxLanes {
  using V = typename Simd::V;
  V ox, oy, oz, ix, iy, iz, ex, ey, ez, tmin;
  PlaneOffsets<Simd::kWidth> planes;
  explicit BoxLanes(const RayData& r)
      : ox(Simd::broadcast(r.origin.x)),
        oy(Simd::broadcast(r.origin.y)),
        oz(Simd::broadcast(r.origin.z)),
        ix(Simd::broadcast(r.slab.inv_dir.x)),
        iy(Simd::broadcast(r.slab.inv_dir.y)),
        iz(Simd::broadcast(r.slab.inv_dir.z)),
        ex(Simd::broadcast(r.slab.inv_dir_exit.x)),
        ey(Simd::broadcast(r.slab.inv_dir_exit.y)),
        ez(Simd::broadcast(r.slab.inv_dir_exit.z)),
        tmin(Simd::broadcast(r.tmin)),
        planes(r.slab.inv_dir) {}
};

/// slab_span on all children of a node, limited to [tmin, t_limit]: bit k of the result says whether child k may
/// hold a hit no farther than t_limit; entry receives the tmin-clamped entry distances. Empty slots have (positive,
/// quiet) NaN planes, which must reach `entry` and fail the compare: SSE's float max returns its second operand when
/// either is NaN; Avx's integer max ranks a positive NaN above every number.
template <typename Simd, typename Node>
inline int hit_boxes(const Node& node, const BoxLanes<Simd>& r, typename Simd::V t_limit, typename Simd::V& entry) {
  using V = typename Simd::V;
  const PlaneOffsets<Simd::kWidth>& p = r.planes;
  auto plane_t = [&](uint32_t offset, V origin, V inverse) {
    return Simd::mul(Simd::sub(Simd::load(plane_row(node, offset)), origin), inverse);
  };
  const V tx0 = plane_t(p.near[0], r.ox, r.ix), ty0 = plane_t(p.near[1], r.oy, r.iy);
  const V tz0 = plane_t(p.near[2], r.oz, r.iz);
  const V tx1 = plane_t(p.far[0], r.ox, r.ex), ty1 = plane_t(p.far[1], r.oy, r.ey);
  const V tz1 = plane_t(p.far[2], r.oz, r.ez);
  entry = Simd::max(Simd::max(tx0, ty0), Simd::max(r.tmin, tz0));
  const V exit = Simd::min(Simd::min(tx1, ty1), Simd::min(tz1, t_limit));
  return Simd::less_equal_mask(entry, exit);
}

/// Möller–Trumbore on four triangles, as moller_trumbore computes it, with intersect_triangle's first range test:
/// bit k says lane k passed (determinant usable, ray inside the triangle, t inside the ray's interval); t, u, v
/// receive every lane's values when any passed. No early exit before the inside test (they would mispredict more
/// than the work they skip); the range test spares most rays the scalar clamp for the triangle they start on.
inline int moller_trumbore4(const BvhTriangleGroup& g, const RayLanes& r, __m128& t, __m128& u, __m128& v) {
  const __m128 e1x = _mm_load_ps(g.e1[0]), e1y = _mm_load_ps(g.e1[1]), e1z = _mm_load_ps(g.e1[2]);
  const __m128 e2x = _mm_load_ps(g.e2[0]), e2y = _mm_load_ps(g.e2[1]), e2z = _mm_load_ps(g.e2[2]);
  // p = cross(dir, e2), written as glm::cross writes it.
  const __m128 px = _mm_sub_ps(_mm_mul_ps(r.dy, e2z), _mm_mul_ps(e2y, r.dz));
  const __m128 py = _mm_sub_ps(_mm_mul_ps(r.dz, e2x), _mm_mul_ps(e2z, r.dx));
  const __m128 pz = _mm_sub_ps(_mm_mul_ps(r.dx, e2y), _mm_mul_ps(e2x, r.dy));
  // glm::dot sums x, y, then z.
  const __m128 det = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e1x, px), _mm_mul_ps(e1y, py)), _mm_mul_ps(e1z, pz));
  const __m128 sx = _mm_sub_ps(r.ox, _mm_load_ps(g.v0[0]));
  const __m128 sy = _mm_sub_ps(r.oy, _mm_load_ps(g.v0[1]));
  const __m128 sz = _mm_sub_ps(r.oz, _mm_load_ps(g.v0[2]));
  const __m128 u_num = _mm_add_ps(_mm_add_ps(_mm_mul_ps(sx, px), _mm_mul_ps(sy, py)), _mm_mul_ps(sz, pz));
  // q = cross(s, e1)
  const __m128 qx = _mm_sub_ps(_mm_mul_ps(sy, e1z), _mm_mul_ps(e1y, sz));
  const __m128 qy = _mm_sub_ps(_mm_mul_ps(sz, e1x), _mm_mul_ps(e1z, sx));
  const __m128 qz = _mm_sub_ps(_mm_mul_ps(sx, e1y), _mm_mul_ps(e1x, sy));
  const __m128 v_num = _mm_add_ps(_mm_add_ps(_mm_mul_ps(r.dx, qx), _mm_mul_ps(r.dy, qy)), _mm_mul_ps(r.dz, qz));
  const __m128 sign_bit = _mm_set1_ps(-0.0f);
  const __m128 abs_det = _mm_andnot_ps(sign_bit, det);
  const __m128 det_sign = _mm_and_ps(sign_bit, det);  // multiplying by -1 where det < 0 flips this bit
  const __m128 u_signed = _mm_xor_ps(u_num, det_sign), v_signed = _mm_xor_ps(v_num, det_sign);
  const __m128 zero = _mm_setzero_ps();
  const __m128 usable =
      _mm_and_ps(_mm_cmpge_ps(abs_det, _mm_set1_ps(kMinDeterminant)), _mm_cmplt_ps(abs_det, _mm_set1_ps(kInfinity)));
  const __m128 inside = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(u_signed, zero), _mm_cmpge_ps(v_signed, zero)),
                                   _mm_cmple_ps(_mm_add_ps(u_signed, v_signed), abs_det));
  const __m128 crosses = _mm_and_ps(usable, inside);
  if (_mm_movemask_ps(crosses) == 0) return 0;
  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  t = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(e2x, qx), _mm_mul_ps(e2y, qy)), _mm_mul_ps(e2z, qz)), inv_det);
  const __m128 in_range = _mm_and_ps(_mm_cmpgt_ps(t, r.tmin), _mm_cmplt_ps(t, r.tmax));
  const int mask = _mm_movemask_ps(_mm_and_ps(crosses, in_range));
  if (mask == 0) return 0;
  u = _mm_mul_ps(u_num, inv_det);
  v = _mm_mul_ps(v_num, inv_det);
  return mask;
}

/// What clamp4 needs of the ray, broadcast: the slab test's inverse direction, its exit-scaled form, and which
/// plane of each axis is the near one. Closest-hit queries only (any-hit ones keep the scalar clamp, below).
struct ClampLanes {
  __m128 inv[3], inv_exit[3];
  bool negative[3];
  explicit ClampLanes(const RayData& r)
      : inv{_mm_set1_ps(r.slab.inv_dir.x), _mm_set1_ps(r.slab.inv_dir.y), _mm_set1_ps(r.slab.inv_dir.z)},
        inv_exit{_mm_set1_ps(r.slab.inv_dir_exit.x), _mm_set1_ps(r.slab.inv_dir_exit.y),
                 _mm_set1_ps(r.slab.inv_dir_exit.z)},
        negative{r.slab.inv_dir.x < 0.0f, r.slab.inv_dir.y < 0.0f, r.slab.inv_dir.z < 0.0f} {}
};

/// The rest of intersect_triangle (clamp_to_triangle_box, then the ray's open interval) on the lanes set in `mask`,
/// four at once: clamps `t` and returns the lanes whose clamped t is still a hit. Each operation repeats the scalar
/// one with its operand order, since SSE min/max return their second operand on ties (+0 against -0) where glm's
/// and std's return the first. On closest-hit queries this beat one scalar clamp call per lane: conference
/// primary rays 6-9% faster, bounce rays 2-3% (session 8, BENCHMARKS.md); any-hit queries, which stop at their first
/// hit, were slower with it.
inline int clamp4(const BvhTriangleGroup& g, const RayLanes& r, const ClampLanes& c, int mask, __m128& t) {
  __m128 lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const __m128 v0 = _mm_load_ps(g.v0[a]);
    const __m128 v1 = _mm_add_ps(v0, _mm_load_ps(g.e1[a]));
    const __m128 v2 = _mm_add_ps(v0, _mm_load_ps(g.e2[a]));
    lo[a] = _mm_min_ps(v2, _mm_min_ps(v1, v0));  // glm::min(glm::min(v0, v1), v2)
    hi[a] = _mm_max_ps(v2, _mm_max_ps(v1, v0));  // glm::max(glm::max(v0, v1), v2)
  }
  // max_abs_component's three values are non-negative and never NaN, so their order cannot matter.
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  auto max_abs = [&](const __m128* v) {
    return _mm_max_ps(_mm_max_ps(_mm_and_ps(v[0], abs_mask), _mm_and_ps(v[1], abs_mask)), _mm_and_ps(v[2], abs_mask));
  };
  const __m128 pad = _mm_mul_ps(_mm_set1_ps(kTrianglePadding), _mm_max_ps(max_abs(hi), max_abs(lo)));  // std::max
  const __m128 origin[3] = {r.ox, r.oy, r.oz};
  __m128 near_t[3], far_t[3];
  for (int a = 0; a < 3; ++a) {
    const __m128 box_lo = _mm_sub_ps(lo[a], pad), box_hi = _mm_add_ps(hi[a], pad);
    near_t[a] = _mm_mul_ps(_mm_sub_ps(c.negative[a] ? box_hi : box_lo, origin[a]), c.inv[a]);
    far_t[a] = _mm_mul_ps(_mm_sub_ps(c.negative[a] ? box_lo : box_hi, origin[a]), c.inv_exit[a]);
  }
  // slab_span's max_f / min_f are SSE's max / min, operand for operand.
  const __m128 entry = _mm_max_ps(_mm_max_ps(near_t[0], near_t[1]), near_t[2]);
  const __m128 exit = _mm_min_ps(_mm_min_ps(far_t[0], far_t[1]), far_t[2]);
  t = _mm_min_ps(_mm_max_ps(t, entry), exit);  // a NaN t becomes `entry`, as in clamp_to_triangle_box
  const __m128 hit =
      _mm_and_ps(_mm_cmple_ps(entry, exit), _mm_and_ps(_mm_cmpgt_ps(t, r.tmin), _mm_cmplt_ps(t, r.tmax)));
  return mask & _mm_movemask_ps(hit);
}

inline float lane(__m128 x, uint32_t k) {
  alignas(16) float values[4];
  _mm_store_ps(values, x);
  return values[k];
}

/// The rest of intersect_triangle for one lane that passed Möller–Trumbore: the clamp into the triangle's box, then
/// the ray's open interval. Any-hit queries only (closest-hit ones use clamp4).
inline bool finish_lane(const RayData& r, const BvhTriangleGroup& g, uint32_t k, float& t) {
  const Vec3 v0(g.v0[0][k], g.v0[1][k], g.v0[2][k]);
  const Vec3 e1(g.e1[0][k], g.e1[1][k], g.e1[2][k]);
  const Vec3 e2(g.e2[0][k], g.e2[1][k], g.e2[2][k]);
  return clamp_to_triangle_box(r.slab, v0, e1, e2, t) && t > r.tmin && t < r.tmax;
}

}  // namespace
}  // namespace lueur
