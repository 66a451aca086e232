// Vector aliases over GLM and the small geometric helpers every layer shares.
// Depends on GLM only.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace lueur {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Largest absolute coordinate: the scale against which ray offsets are measured.
inline float max_abs_component(const Vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

/// Relative luminance (Rec. 709 primaries) of a linear RGB value.
inline float luminance(const Vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

inline bool is_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Orthonormal basis around a unit normal (Duff et al., "Building an Orthonormal Basis, Revisited").
struct Frame {
  Vec3 tangent, bitangent, normal;

  static Frame from_normal(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y), n};
  }
  Vec3 to_world(const Vec3& local) const { return local.x * tangent + local.y * bitangent + local.z * normal; }
  Vec3 to_local(const Vec3& world) const {
    return Vec3(glm::dot(world, tangent), glm::dot(world, bitangent), glm::dot(world, normal));
  }
};

}  // namespace lueur
