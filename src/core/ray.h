// Rays, hit records and axis-aligned boxes: the vocabulary between the scene, the BVH and the passes.
#pragma once

#include "core/math.h"

namespace lueur {

inline constexpr uint32_t kNoHit = 0xffffffffu;

/// A ray o + t d for t in (tmin, tmax). `dir` need not be normalised.
struct Ray {
  Vec3 origin{0.0f};
  Vec3 dir{0.0f, 0.0f, 1.0f};
  float tmin = 0.0f;
  float tmax = kInfinity;
};

/// Closest hit: the triangle (scene index), the distance along the ray and barycentrics of vertices 1 and 2.
struct Hit {
  float t = kInfinity;
  uint32_t triangle = kNoHit;
  float u = 0.0f, v = 0.0f;
  bool found() const { return triangle != kNoHit; }
};

struct Box3 {
  Vec3 lo{kInfinity};
  Vec3 hi{-kInfinity};

  void expand(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void expand(const Box3& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3 extent() const { return empty() ? Vec3(0.0f) : hi - lo; }
  Vec3 center() const { return 0.5f * (lo + hi); }
  float diagonal() const { return glm::length(extent()); }
  /// Surface area; zero for an empty box.
  float area() const {
    const Vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

/// Offsets a surface point along its geometric normal so that a ray leaving it does not hit its own triangle.
/// The offset scales with the magnitude of the coordinates, where float spacing grows.
inline Vec3 offset_origin(const Vec3& p, const Vec3& geometric_normal, const Vec3& toward) {
  const float eps = 1e-4f * (1.0f + max_abs_component(p)) * 1e-1f;
  return glm::dot(geometric_normal, toward) >= 0.0f ? p + eps * geometric_normal : p - eps * geometric_normal;
}

}  // namespace lueur
