// ln: the light of the second and later bounces after the pixel's surface p, every path that L1 (p -> light) and
// L2 (p -> q -> light, by q's shadow rays) leave out, up to the bounce limit. Path tracing from p with next-event
// estimation at every vertex past q, multiple importance sampling (the power heuristic) wherever a light can be
// found both by a shadow ray and by the bounce direction, and Russian roulette after the first few vertices. Light
// that reaches a surface only through mirrors or glass (caustics) is here: shadow rays cannot find it, bounce
// directions do. Depends on the traced scene, the BRDF and the specular lobes.
#pragma once

#include <cstdint>

#include "core/pixel_sampler.h"
#include "passes/render_settings.h"
#include "integrator/indirect_light.h"
#include "integrator/traced_scene.h"

namespace lueur {

/// ln at `p`, reached after `bounces_before` scattering events (the camera's mirrors and glass): the average of
/// settings.ln_rays paths, samples `first_sample` onwards of `sampler`, each with bounces up to
/// settings.max_bounces in all. Vertex v of a path draws dimensions 4v to 4v + 3 of its sample, whatever happened
/// before it. A specular material at p scatters by its Lambert base alone (the camera's path chose it). The
/// head-light is left out. Adds the rays it traced to `rays_traced`.
/// Path k < `shared_count` starts along L2's bounce k (`shared[k]`, indirect_light.h) instead of a direction of its
/// own: the same cosine-weighted distribution, one ray fewer.
///
/// With `screen` (the reuse modes that read it), a vertex past q that the camera sees directly, on a surface whose
/// BRDF is the same toward every direction (Lambert, or the report's mix without a lobe), takes its L1 whole from
/// the pixel that sees it, as L2 does at q (the report's reuse, one bounce further), instead of one shadow ray; the
/// emitter its bounce direction meets then counts for nothing, as in L2. Not with --reuse-diffuse-only, the
/// head-light (in the screen's L1, not in ln) or a colour map.
struct ScreenAccess {
  const Camera* camera = nullptr;
  const ScreenBuffer* screen = nullptr;
};
Vec3 estimate_further_bounces(const TracedScene& traced, const SurfacePoint& p, const RenderSettings& settings,
                              int bounces_before, PixelSampler& sampler, uint64_t first_sample,
                              uint64_t& rays_traced, const SharedBounce* shared = nullptr, int shared_count = 0,
                              const ScreenAccess* screen = nullptr);

}  // namespace lueur
