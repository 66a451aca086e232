// Sampling warps from the unit square, each next to its pdf. Depends on core/math.h only.
#pragma once

#include "core/math.h"

namespace lueur {

/// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2 (square-root parameterisation,
/// Shirley & Chiu / pbrt: pdf 1 / area).
inline Vec2 sample_uniform_triangle(float u1, float u2) {
  const float su = std::sqrt(u1);
  return Vec2(su * (1.0f - u2), su * u2);
}

/// Cosine-weighted direction on the hemisphere around +z (Dutré's Global Illumination Compendium, formula 35):
/// phi = 2 pi u1, theta = acos(sqrt(u2)), pdf = cos(theta) / pi.
inline Vec3 sample_cosine_hemisphere(float u1, float u2) {
  const float phi = 2.0f * kPi * u1;
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - u2));
  return Vec3(std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, std::sqrt(u2));
}

inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

}  // namespace lueur
