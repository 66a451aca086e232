// Mirrors and smooth glass: the Fresnel reflectance, refraction, and the one-number choice of a lobe.
#include "integrator/specular.h"

#include <algorithm>
#include <cmath>

namespace lueur {

SpecularParts specular_parts(const Material& m, const Vec3& kd) {
  SpecularParts parts;
  if (m.surface == SurfaceKind::kMirror) {
    const float total = std::max({1.0f, kd.r + m.ks.r, kd.g + m.ks.g, kd.b + m.ks.b});
    parts.base = kd / total;
    parts.specular = m.ks / total;
  } else if (m.surface == SurfaceKind::kGlass) {
    parts.base = glm::clamp(kd, Vec3(0.0f), Vec3(1.0f));
    parts.specular = Vec3(1.0f) - parts.base;
  } else {
    parts.base = kd;
  }
  return parts;
}

float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (parallel * parallel + perpendicular * perpendicular);
}

bool refract(const Vec3& wo, const Vec3& n, float eta, Vec3& wt) {
  const float cos_i = glm::dot(wo, n);
  const float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  wt = glm::normalize(-wo / eta + (cos_i / eta - cos_t) * n);
  return true;
}

float base_probability(const Material& m, const Vec3& kd) {
  const SpecularParts parts = specular_parts(m, kd);
  const float base = luminance(parts.base), specular = luminance(parts.specular);
  return base + specular > 0.0f ? base / (base + specular) : 0.0f;
}

SpecularSample sample_specular(const Material& m, const Vec3& kd, const Vec3& n, const Vec3& g, const Vec3& wo,
                               bool entering, float u) {
  SpecularSample s;
  const SpecularParts parts = specular_parts(m, kd);
  const float base = luminance(parts.base), specular = luminance(parts.specular);
  if (!(base + specular > 0.0f)) return s;
  s.base_probability = base / (base + specular);
  if (u < s.base_probability) {
    s.lobe = SpecularLobe::kBase;
    s.weight = parts.base / s.base_probability;
    return s;
  }
  const float specular_probability = 1.0f - s.base_probability;
  const float v = std::min((u - s.base_probability) / specular_probability, 0x1.fffffep-1f);
  Vec3 weight = parts.specular / specular_probability;
  bool reflects = true;
  if (m.surface == SurfaceKind::kGlass) {
    const float eta = entering ? m.ior : 1.0f / m.ior;
    // Reflection with probability F, transmission with 1 - F: F cancels from the weight of either.
    if (v >= fresnel_dielectric(glm::dot(wo, n), eta)) {
      reflects = false;
      Vec3 wt(0.0f);
      if (!refract(wo, n, eta, wt) || glm::dot(wt, g) >= 0.0f) return SpecularSample{};
      s.lobe = SpecularLobe::kTransmit;
      s.dir = wt;
      weight *= m.tf;
    }
  }
  if (reflects) {
    s.dir = reflect(wo, n);
    if (glm::dot(s.dir, g) <= 0.0f) return SpecularSample{};
    s.lobe = SpecularLobe::kReflect;
  }
  s.weight = weight;
  return s;
}

}  // namespace lueur
