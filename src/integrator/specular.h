// Mirrors and smooth glass (the MTL's ray-traced illumination models): perfectly specular lobes beside an optional
// Lambert base, the Fresnel reflectance of a dielectric, and the choice of one lobe per scattering. Depends on the
// scene layer (Material) and core.
#pragma once

#include "core/math.h"
#include "scene/scene.h"

namespace lueur {

/// A specular material's reflectance shared out so that the sum never exceeds what arrives: the Lambert base and
/// the specular part. A mirror's Kd + Ks is scaled down as a whole where a channel passes 1; glass gives the base Kd
/// (at most 1) and the dielectric the rest, 1 - Kd, of which Fresnel reflects F and transmits (1 - F) Tf.
struct SpecularParts {
  Vec3 base{0.0f};      ///< the Lambert base's albedo
  Vec3 specular{0.0f};  ///< the mirror's reflectance, or the share the dielectric scatters
};
SpecularParts specular_parts(const Material& m, const Vec3& kd);

/// Fresnel reflectance of a smooth dielectric boundary for unpolarised light arriving at cosine `cos_i` (> 0, on the
/// side it arrives from) where `eta` is the index beyond the boundary over the index before it. 1 beyond the
/// critical angle (total internal reflection).
float fresnel_dielectric(float cos_i, float eta);

/// The mirror direction of `wo` about the unit normal `n` (wo and the result point away from the surface).
inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return 2.0f * glm::dot(wo, n) * n - wo; }

/// The direction refracted from `wo` (pointing away from the surface, on the side of the unit normal `n`) into the
/// other side, `eta` as for fresnel_dielectric; false under total internal reflection.
bool refract(const Vec3& wo, const Vec3& n, float eta, Vec3& wt);

enum class SpecularLobe : int { kNone = 0, kBase, kReflect, kTransmit };

/// One scattering at a specular material, its lobe chosen by one number: the base or the specular part by their
/// luminance, then, for glass, reflection with probability F. `weight` is what the path's throughput is multiplied
/// by: the lobe's albedo over the probability of choosing it (for the base, its albedo over that probability: the
/// caller samples the Lambert direction and keeps its cosine / pdf = pi, as base / pi x pi).
struct SpecularSample {
  SpecularLobe lobe = SpecularLobe::kNone;
  Vec3 dir{0.0f};     ///< reflect and transmit: the new unit direction
  Vec3 weight{0.0f};  ///< the throughput's factor
  float base_probability = 0.0f;  ///< the probability of choosing the base (the pdf of a base direction scales by it)
};

/// Samples the lobe at a surface with unit shading normal `n` and unit geometric normal `g` (both on the side of
/// `wo`), `entering` when `wo` lies on the side the triangle's winding faces (glass: outside, index 1; the other
/// side holds index m.ior). A reflected direction below the geometric surface, or a transmitted one above it, ends
/// the path (kNone): the shading normal bent it where no light goes.
SpecularSample sample_specular(const Material& m, const Vec3& kd, const Vec3& n, const Vec3& g, const Vec3& wo,
                               bool entering, float u);

/// The probability that sample_specular chooses the base: what a Lambert direction's pdf is scaled by there.
float base_probability(const Material& m, const Vec3& kd);

}  // namespace lueur
