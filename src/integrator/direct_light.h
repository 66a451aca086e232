// L1: direct light at a surface point from shadow rays to points sampled on emissive triangles.
// Depends on the traced scene and the BRDF.
#pragma once

#include "core/pixel_sampler.h"
#include "passes/render_settings.h"
#include "integrator/traced_scene.h"

namespace lueur {

/// A shadow ray runs from its origin to the light point (dir = point - origin, so t = 1 at the point) and stops just
/// short of the light itself.
inline constexpr float kShadowReach = 1.0f - 1e-4f;

/// Whether the light point at `origin + to_point` is unoccluded: one shadow ray from `origin`, stopping just short of
/// the point (kShadowReach), counted in `rays_traced`.
bool light_reaches(const TracedScene& traced, const Vec3& origin, const Vec3& to_point, uint64_t& rays_traced);

struct DirectLightOptions {
  LightStrategy strategy = LightStrategy::kArea;
  int rays = 16;  ///< samples; with kAll each sample sends one shadow ray to every emitter
  float blinn_k = 0.7f;
  bool specular_only = false;  ///< evaluate only the view-dependent part of the BRDF (BRDF minus its diffuse part)
  /// The head-light (make_camera_light), sampled once per sample besides the scene's emitters; nullptr: none.
  const EmitterRecord* camera_light = nullptr;
};

/// Radiance reflected towards `sp.wo` from the emitters, averaged over `options.rays` samples: samples
/// `first_sample` onwards of `sampler`, each drawing the light choice (1D) and the point on the light (2D), or with
/// kAll one point per emitter. Unbiased for every strategy. Adds the shadow rays it traced to `rays_traced`. When
/// `diffuse_part` is given it receives, from the same samples, the part reflected by the view-independent term of
/// the BRDF alone. When `arriving` is given it receives the light arriving from the emitters, weighted by cos at the
/// surface and without the BRDF, averaged over the same samples (what the L1 store keeps).
Vec3 estimate_direct_light(const TracedScene& traced, const SurfacePoint& sp, const DirectLightOptions& options,
                           PixelSampler& sampler, uint64_t first_sample, uint64_t& rays_traced,
                           Vec3* diffuse_part = nullptr, Vec3* arriving = nullptr);

/// estimate_direct_light at `count` surface points (without `diffuse_part`): point i's L1 from samples
/// `first_samples[i]` onwards into `l1[i]`, and its arriving light into `arriving[i]` when given. The same values,
/// byte for byte, as a call per point; but the samples of several points share a batch's lanes (L2's bounce hits
/// recompute L1 with 2 rays each, a batch of 16 lanes holds 8 of them).
void estimate_direct_light_at_points(const TracedScene& traced, const SurfacePoint* const* points,
                                     const uint64_t* first_samples, size_t count, const DirectLightOptions& options,
                                     PixelSampler& sampler, uint64_t& rays_traced, Vec3* l1, Vec3* arriving = nullptr);

}  // namespace lueur
