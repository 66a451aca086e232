// The report's Blinn-Phong BRDF, and the Lambert base of mirrors and glass (their specular lobes are in specular.h:
// no shadow ray can find a direction of zero width). Depends on the scene layer (Material).
#pragma once

#include "integrator/specular.h"
#include "scene/scene.h"

namespace lueur {

/// Whether a surface of this material reflects any light: a black one (an emitter's, or the light rig's) has no L1
/// to estimate, so no shadow ray is spent on it.
inline bool reflects_light(const Material& m) {
  return m.has_specular() || m.diffuse_texture >= 0 || m.kd.r > 0.0f || m.kd.g > 0.0f || m.kd.b > 0.0f;
}

/// Normalised Blinn-Phong lobe (n + 8) / (8 pi) cos^n(theta_h).
inline float blinn_phong_lobe(float cos_theta_h, float exponent) {
  if (cos_theta_h <= 0.0f) return 0.0f;
  // Exponent 0 (an MTL without Ns, as most are) makes the lobe a constant: no call into libm's pow.
  const float power = exponent == 0.0f ? 1.0f : std::pow(cos_theta_h, exponent);
  return (exponent + 8.0f) * (1.0f / (8.0f * kPi)) * power;
}

// Every function takes the diffuse albedo `kd` at the point apart from the material: it is the material's Kd, or its
// colour map at the point (Scene::albedo).

/// BRDF for light arriving along `wi` and leaving along `wo` (both unit, pointing away from the surface) at a point
/// with shading normal `n`. With Ks: Kd / pi + Ks lobe. Without Ks: the report's mix Kd (K / pi + (1 - K) lobe).
/// A mirror or glass: its Lambert base alone.
inline Vec3 eval_brdf(const Material& m, const Vec3& kd, const Vec3& n, const Vec3& wi, const Vec3& wo, float blinn_k) {
  if (m.is_specular()) return specular_parts(m, kd).base * kInvPi;
  // Pure Lambert (no Ks, K = 1): the lobe's weight is zero, so neither it nor the half vector is needed.
  if (!m.has_specular() && blinn_k >= 1.0f) return kd * kInvPi;
  const Vec3 h = wi + wo;
  const float h_length = glm::length(h);
  const float cos_theta_h = h_length > 0.0f ? glm::dot(n, h) / h_length : 0.0f;
  const float lobe = blinn_phong_lobe(cos_theta_h, m.ns);
  if (m.has_specular()) return kd * kInvPi + m.ks * lobe;
  return kd * (blinn_k * kInvPi + (1.0f - blinn_k) * lobe);
}

/// The view-independent part of the BRDF (what a Lambertian surface would reflect).
inline Vec3 eval_brdf_diffuse(const Material& m, const Vec3& kd, float blinn_k) {
  if (m.is_specular()) return specular_parts(m, kd).base * kInvPi;
  return m.has_specular() ? kd * kInvPi : kd * (blinn_k * kInvPi);
}

/// Whether the BRDF toward `wo` is the same for every direction of arriving light above the surface, so that L1 is
/// that constant times the arriving light: Lambert (no Ks, K = 1), or the report's mix whose lobe has exponent 0 (an
/// MTL without Ns) seen from above the shading normal `n` (every half vector then lies above it, where that lobe is
/// the constant 1 / pi), or the Lambert base of a mirror or glass.
inline bool brdf_is_constant(const Material& m, float blinn_k, const Vec3& n, const Vec3& wo) {
  if (m.is_specular()) return true;
  if (m.has_specular()) return false;
  return blinn_k >= 1.0f || (m.ns == 0.0f && glm::dot(n, wo) > 0.0f);
}

/// That constant, where brdf_is_constant holds: what eval_brdf gives for any light direction above the surface.
inline Vec3 constant_brdf(const Material& m, const Vec3& kd, float blinn_k) {
  if (m.is_specular()) return specular_parts(m, kd).base * kInvPi;
  if (blinn_k >= 1.0f) return kd * kInvPi;
  return kd * (blinn_k * kInvPi + (1.0f - blinn_k) * blinn_phong_lobe(1.0f, 0.0f));
}

}  // namespace lueur
