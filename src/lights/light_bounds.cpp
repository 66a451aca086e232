// Bounds of a set of emitters, for the `importance` light choice.
#include "lights/light_bounds.h"

#include <limits>

namespace lueur {

LightBounds bound_emitters(const std::vector<EmitterRecord>& records, const std::vector<double>& weights,
                           const uint32_t* indices, size_t count, double power_scale) {
  Vec3 lo(kInfinity), hi(-kInfinity);
  glm::dvec3 normal_sum(0.0);
  double area_sum = 0.0, power = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const EmitterRecord& e = records[indices[k]];
    lo = glm::min(lo, glm::min(e.p0, glm::min(e.p1, e.p2)));
    hi = glm::max(hi, glm::max(e.p0, glm::max(e.p1, e.p2)));
    normal_sum += static_cast<double>(e.area) * glm::dvec3(e.normal);
    area_sum += e.area;
    power += weights[indices[k]];
  }
  LightBounds b;
  const Vec3 centre = 0.5f * (lo + hi);
  b.cx = centre.x, b.cy = centre.y, b.cz = centre.z;
  // Half the diagonal, made a hair larger so that rounding never leaves a corner outside.
  b.radius = std::max(0.5f * glm::length(hi - lo) * (1.0f + 1e-5f), std::numeric_limits<float>::min());
  const double length = glm::length(normal_sum);
  Vec3 axis(0.0f, 0.0f, 1.0f);
  float cos_spread = -1.0f;
  if (length > 1e-6 * area_sum) {
    axis = Vec3(normal_sum / length);
    cos_spread = 1.0f;
    for (size_t k = 0; k < count; ++k) cos_spread = std::min(cos_spread, glm::dot(axis, records[indices[k]].normal));
    // Rounding must not narrow the cone: widen it by a hair, and to every direction once it is a half-space or more.
    cos_spread = cos_spread > 1e-3f ? std::min(cos_spread, 1.0f) - 1e-5f : -1.0f;
  }
  b.ax = axis.x, b.ay = axis.y, b.az = axis.z;
  b.cos_spread = cos_spread;
  const Vec3 half = 0.5f * (hi - lo) * (1.0f + 1e-5f);
  b.ex = half.x, b.ey = half.y, b.ez = half.z;
  // Where the point must be for some emitter of the set to face it: in front of the plane through the lowest corner
  // along the axis, by up to tilt x (distance to the farthest corner) when the normals lean off the axis.
  float lowest = kInfinity;
  double tilt = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const EmitterRecord& e = records[indices[k]];
    lowest = std::min({lowest, glm::dot(axis, e.p0), glm::dot(axis, e.p1), glm::dot(axis, e.p2)});
    tilt = std::max(tilt, glm::length(glm::dvec3(e.normal) - glm::dvec3(axis)));
  }
  b.lowest = lowest;
  b.tilt = static_cast<float>(tilt) + 1e-6f;  // the normals' own rounding
  b.power = static_cast<float>(power * power_scale);
  return b;
}

}  // namespace lueur
