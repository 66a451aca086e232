// Queries on Lueur's BVH: the shared ray-triangle test, the closest-hit and the any-hit traversals.
// Depends on core (math, ray) and bvh.h only; this is the renderer's hot path, so no allocation and no virtual calls.

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

/// Slab test: the span [entry, exit] of the ray's line inside the box, not yet limited to the ray's interval. Each
/// bound is monotone in the box, so a box inside another gets a span inside the other's: the BVH's exact agreement
/// with the brute-force loop rests on the node test and the triangle clamp both using this function.
inline void slab_span(const Vec3& lo, const Vec3& hi, const Vec3& origin, const Vec3& inv_dir, float& entry,
                      float& exit) {
  const float tx0 = (lo.x - origin.x) * inv_dir.x;
  const float tx1 = (hi.x - origin.x) * inv_dir.x;
  const float ty0 = (lo.y - origin.y) * inv_dir.y;
  const float ty1 = (hi.y - origin.y) * inv_dir.y;
  const float tz0 = (lo.z - origin.z) * inv_dir.z;
  const float tz1 = (hi.z - origin.z) * inv_dir.z;
  entry = max_f(max_f(min_f(tx0, tx1), min_f(ty0, ty1)), min_f(tz0, tz1));
  exit = min_f(min_f(max_f(tx0, tx1), max_f(ty0, ty1)), max_f(tz0, tz1)) * kExitScale;
}

/// What every box test of one ray needs, computed once per query.
struct RayData {
  Vec3 origin;
  Vec3 dir;
  Vec3 inv_dir;
  float tmin;
  float tmax;
  explicit RayData(const Ray& ray)
      : origin(ray.origin), dir(ray.dir), inv_dir(safe_inverse(ray.dir)), tmin(ray.tmin), tmax(ray.tmax) {}
};

/// True if the ray meets the node box at some t in [tmin, t_limit]; `entry` is the tmin-clamped entry distance.
/// The limit is inclusive so that an equally distant triangle with a lower id is still found.
inline bool hit_box(const BvhNode& node, const RayData& r, float t_limit, float& entry) {
  float box_entry, box_exit;
  slab_span(node.lo, node.hi, r.origin, r.inv_dir, box_entry, box_exit);
  entry = max_f(box_entry, r.tmin);
  return entry <= box_exit && entry <= t_limit;
}

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

/// Möller–Trumbore without the range test on t.
inline bool moller_trumbore(const Vec3& origin, const Vec3& dir, const Vec3& v0, const Vec3& e1, const Vec3& e2,
                            float& t, float& u, float& v) {
  const Vec3 p = glm::cross(dir, e2);
  const float det = glm::dot(e1, p);
  // Exactly zero: the ray is parallel to the plane or the triangle has no area. Non-finite: overflowing edges.
  if (det == 0.0f || !std::isfinite(det)) return false;
  const float inv_det = 1.0f / det;
  const Vec3 s = origin - v0;
  u = glm::dot(s, p) * inv_det;
  // Written so that a NaN (inv_det overflowing on a denormal determinant) is rejected.
  if (!(u >= 0.0f && u <= 1.0f)) return false;
  const Vec3 q = glm::cross(s, e1);
  v = glm::dot(dir, q) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return false;
  t = glm::dot(e2, q) * inv_det;
  return true;
}

/// Moves a Möller–Trumbore t into the ray's span inside the triangle's box. Only runs on the rare candidate hits.
/// The t of an ill-conditioned determinant (slivers, grazing rays) can land far from the triangle; the true hit
/// lies inside the box, so the clamp only ever brings t closer to it.
inline bool clamp_to_triangle_box(const Vec3& origin, const Vec3& inv_dir, const Vec3& v0, const Vec3& e1,
                                  const Vec3& e2, float& t) {
  const Box3 box = triangle_box(v0, e1, e2);
  float entry, exit;
  slab_span(box.lo, box.hi, origin, inv_dir, entry, exit);
  if (!(entry <= exit)) return false;
  t = min_f(max_f(t, entry), exit);  // a NaN t becomes `entry`
  return true;
}

/// The whole shared test; the BVH passes its precomputed inverse direction, which is bit-identical to the one
/// intersect_triangle computes.
inline bool triangle_hit(const Vec3& origin, const Vec3& dir, const Vec3& inv_dir, const BvhTriangle& tri, float& t,
                         float& u, float& v) {
  return moller_trumbore(origin, dir, tri.v0, tri.e1, tri.e2, t, u, v) &&
         clamp_to_triangle_box(origin, inv_dir, tri.v0, tri.e1, tri.e2, t);
}

}  // namespace

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
  Hit hit;
  if (bvh.empty()) return hit;
  const RayData r(ray);
  const BvhNode* nodes = bvh.nodes.data();
  const BvhTriangle* triangles = bvh.triangles.data();

  float best_t = r.tmax;
  uint32_t best_id = kNoHit;
  float best_u = 0.0f, best_v = 0.0f;

  float entry;
  if (!hit_box(nodes[0], r, best_t, entry)) return hit;

  // Far children wait here with their entry distance, so they can be dropped once a closer hit is known.
  struct StackEntry {
    uint32_t node;
    float entry;
  };
  StackEntry stack[kBvhMaxDepth];
  uint32_t size = 0;
  uint32_t current = 0;

  for (;;) {
    const BvhNode& node = nodes[current];
    if (node.count == 0) {
      float entry_a, entry_b;
      const bool hit_a = hit_box(nodes[node.first], r, best_t, entry_a);
      const bool hit_b = hit_box(nodes[node.first + 1], r, best_t, entry_b);
      if (hit_a && hit_b) {
        // Nearer child first: its hits shrink best_t and let the other be culled.
        if (entry_b < entry_a) {
          stack[size++] = {node.first, entry_a};
          current = node.first + 1;
        } else {
          stack[size++] = {node.first + 1, entry_b};
          current = node.first;
        }
        continue;
      }
      if (hit_a || hit_b) {
        current = hit_a ? node.first : node.first + 1;
        continue;
      }
    } else {
      const BvhTriangle* tri = triangles + node.first;
      const BvhTriangle* const end = tri + node.count;
      for (; tri != end; ++tri) {
        float t, u, v;
        if (!triangle_hit(r.origin, r.dir, r.inv_dir, *tri, t, u, v)) continue;
        if (!(t > r.tmin && t < r.tmax)) continue;
        // Equal distances go to the lowest input index, whichever leaf was reached first.
        if (t < best_t || (t == best_t && tri->id < best_id)) {
          best_t = t;
          best_id = tri->id;
          best_u = u;
          best_v = v;
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
      --size;
    } while (stack[size].entry > best_t);
    current = stack[size].node;
  }
}

bool intersect_any(const Bvh& bvh, const Ray& ray) {
  if (bvh.empty()) return false;
  const RayData r(ray);
  const BvhNode* nodes = bvh.nodes.data();
  const BvhTriangle* triangles = bvh.triangles.data();

  float entry;
  if (!hit_box(nodes[0], r, r.tmax, entry)) return false;

  uint32_t stack[kBvhMaxDepth];
  uint32_t size = 0;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (node.count == 0) {
      float entry_a, entry_b;
      const bool hit_a = hit_box(nodes[node.first], r, r.tmax, entry_a);
      const bool hit_b = hit_box(nodes[node.first + 1], r, r.tmax, entry_b);
      if (hit_a && hit_b) {
        stack[size++] = node.first + 1;
        current = node.first;
        continue;
      }
      if (hit_a || hit_b) {
        current = hit_a ? node.first : node.first + 1;
        continue;
      }
    } else {
      const BvhTriangle* tri = triangles + node.first;
      const BvhTriangle* const end = tri + node.count;
      for (; tri != end; ++tri) {
        float t, u, v;
        if (triangle_hit(r.origin, r.dir, r.inv_dir, *tri, t, u, v) && t > r.tmin && t < r.tmax) {
          return true;
        }
      }
    }
    if (size == 0) return false;
    current = stack[--size];
  }
}

}  // namespace lueur
