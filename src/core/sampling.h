// Sampling warps from the unit square, each next to its pdf. Depends on core/math.h only.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace lueur {

/// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2 (square-root parameterisation,
/// Shirley & Chiu / pbrt: pdf 1 / area).
inline Vec2 sample_uniform_triangle(float u1, float u2) {
  const float su = std::sqrt(u1);
  return Vec2(su * (1.0f - u2), su * u2);
}

/// (cos, sin) of 2 pi u for u in [0, 1], without a call into libm: u x 4 is exact, so the reduction to a quarter
/// turn around the nearest multiple of pi/2 loses nothing, and Taylor polynomials of degree 9 and 10 on
/// [-pi/4, pi/4] are within 2e-9 of the true values there. The quadrant then swaps and negates without branches
/// (a sampled angle's quadrant is a coin toss for a branch predictor).
inline Vec2 cos_sin_2pi(float u) {
  const float quarters = u * 4.0f;
  const float nearest = std::nearbyint(quarters);
  const float a = (quarters - nearest) * (kPi / 2.0f);
  const float a2 = a * a;
  const float s =
      a * (1.0f + a2 * (-1.0f / 6.0f + a2 * (1.0f / 120.0f + a2 * (-1.0f / 5040.0f + a2 * (1.0f / 362880.0f)))));
  const float c =
      1.0f +
      a2 * (-0.5f + a2 * (1.0f / 24.0f + a2 * (-1.0f / 720.0f + a2 * (1.0f / 40320.0f + a2 * (-1.0f / 3628800.0f)))));
  const auto quadrant = static_cast<uint32_t>(static_cast<int>(nearest));
  const bool odd = (quadrant & 1u) != 0;
  const float x = odd ? s : c, y = odd ? c : s;
  return Vec2(((quadrant + 1u) & 2u) ? -x : x, (quadrant & 2u) ? -y : y);
}

/// Cosine-weighted direction on the hemisphere around +z (Dutré's Global Illumination Compendium, formula 35):
/// phi = 2 pi u1, theta = acos(sqrt(u2)), pdf = cos(theta) / pi.
inline Vec3 sample_cosine_hemisphere(float u1, float u2) {
  const Vec2 cs = cos_sin_2pi(u1);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - u2));
  return Vec3(cs.x * sin_theta, cs.y * sin_theta, std::sqrt(u2));
}

inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f; }

}  // namespace lueur
