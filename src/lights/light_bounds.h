// Bounds of a set of emitters (a sphere and a box around their triangles, a cone around their normals, the plane
// they all face away from, their power) and the bound those give on what the set can send to a shaded point
// (pbrt-v4's LightBounds::Importance, with Lueur's horizon and facing tests). Shared by the `importance` light
// choice's clusters and the children of each node of the trees inside large clusters, each set weighed at once.
// Depends on lights/emitter.h only.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lights/emitter.h"

namespace lueur {

/// One set's bounds, as plain floats (the clusters keep each field in an array of its own).
struct LightBounds {
  float cx = 0.0f, cy = 0.0f, cz = 0.0f;  ///< centre of the bounding sphere (and box) of its triangles
  float radius = 1.0f;                    ///< that sphere's radius (positive)
  float ax = 0.0f, ay = 0.0f, az = 1.0f;  ///< unit axis of the cone holding its emitters' normals
  float cos_spread = -1.0f;               ///< cosine of that cone's half-angle; -1: they face every way
  float ex = 0.0f, ey = 0.0f, ez = 0.0f;  ///< half extents of the box around its triangles
  float lowest = 0.0f;                    ///< the least of axis . corner over its triangles' corners
  float tilt = 0.0f;                      ///< the largest |normal - axis| over its emitters (0: all along the axis)
  float power = 0.0f;                     ///< its emitters' power, scaled (only ratios matter)
};

/// The bounds of emitters `records[indices[0, count)]`, whose weights (power, or area) are `weights[index]`, with
/// the weights' sum scaled by `power_scale`.
LightBounds bound_emitters(const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
                           const uint32_t* indices, size_t count, double power_scale);

/// A shaded point as the importance bound reads it: position, unit normal (light must arrive on its side) and the
/// normal's absolute components.
struct ImportanceQuery {
  float px, py, pz, nx, ny, nz, abs_nx, abs_ny, abs_nz;
  ImportanceQuery(const Vec3& position, const Vec3& normal)
      : px(position.x),
        py(position.y),
        pz(position.z),
        nx(normal.x),
        ny(normal.y),
        nz(normal.z),
        abs_nx(std::fabs(normal.x)),
        abs_ny(std::fabs(normal.y)),
        abs_nz(std::fabs(normal.z)) {}
};

/// Below this cosine at the surface (relative to the distance to the farthest corner), a set counts as under the
/// horizon.
inline constexpr float kHorizonTolerance = 1e-5f;

// Internal linkage, as bvh_traversal.h's kernels: the AVX2 build of the trees' weighing (light_lanes_avx2.cpp) and
// the baseline one each keep their own copy, and no copy is shared between them at link time.
namespace {
/// cos(max(0, a - b)) for angles a, b in [0, pi] given by their cosines and sines.
inline float cos_of_clamped_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
/// sin(max(0, a - b)), likewise.
inline float sin_of_clamped_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
  return cos_a >= cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}
inline float sine_of(float cosine) { return std::sqrt(std::max(0.0f, 1.0f - cosine * cosine)); }
}  // namespace

/// A bound on the light set `b` can send to the point: power x the best cosine at the surface x the best cosine at
/// the emitters / distance^2 (power / radius^2 inside the sphere), and 0 where its box is wholly below the point's
/// horizon or the point is behind every one of its emitters' planes. Positive wherever some emitter of the set can
/// light the point (up to the tolerances above). Branch-free, so that a loop over many sets vectorises.
[[gnu::always_inline]] inline float light_importance(const ImportanceQuery& q, const LightBounds& b) {
  const float dx = b.cx - q.px, dy = b.cy - q.py, dz = b.cz - q.pz;
  const float d2 = dx * dx + dy * dy + dz * dz;
  const float r2 = b.radius * b.radius;
  // Inside the bounding sphere every direction may reach the set: both cosines are bounded by 1 only.
  const bool inside = !(d2 > r2);
  const float inv_d = 1.0f / std::sqrt(inside ? r2 : d2);
  const float sin_b = std::min(1.0f, b.radius * inv_d), cos_b = sine_of(sin_b);  // the sphere's half-angle
  // At the surface: the angle between the normal and the direction to the centre, less the sphere's half-angle.
  const float cos_i = (q.nx * dx + q.ny * dy + q.nz * dz) * inv_d;
  const float surface = cos_of_clamped_difference(cos_i, sine_of(cos_i), cos_b, sin_b);
  // At the emitters: the angle between the cone's axis and the direction to the point, less the cone's half-angle
  // and the sphere's half-angle.
  const float cos_w = -(b.ax * dx + b.ay * dy + b.az * dz) * inv_d;
  const float sin_w = sine_of(cos_w), cos_o = b.cos_spread, sin_o = sine_of(cos_o);
  const float cos_x = cos_of_clamped_difference(cos_w, sin_w, cos_o, sin_o);
  const float sin_x = sin_of_clamped_difference(cos_w, sin_w, cos_o, sin_o);
  const float emitter = cos_of_clamped_difference(cos_x, sin_x, cos_b, sin_b);
  const float weight = b.power * std::max(surface, 0.0f) * std::max(emitter, 0.0f) * (inv_d * inv_d);
  // Tests that hold close or far: some corner of the box above the horizon, the point in front of some emitter.
  // The first allows for rounding, which decides for an emitter in the surface's own plane (a wall lamp's other
  // triangles, seen from one of them): one whose every point is below a cosine of 1e-5 at the surface sends
  // nothing worth a shadow ray.
  const float reach = std::sqrt(d2) + b.radius;
  const float highest_above = q.nx * dx + q.ny * dy + q.nz * dz + q.abs_nx * b.ex + q.abs_ny * b.ey + q.abs_nz * b.ez;
  const float in_front = b.ax * q.px + b.ay * q.py + b.az * q.pz - b.lowest + b.tilt * reach;
  const bool can_light = (highest_above > kHorizonTolerance * reach) & (in_front > 0.0f);
  return can_light ? (inside ? b.power * inv_d * inv_d : weight) : 0.0f;
}

}  // namespace lueur
