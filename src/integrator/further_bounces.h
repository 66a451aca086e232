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
/// Where ln's vertices past q may take their L1 whole instead of tracing a shadow ray, as L2 does at q; null
/// members: not there. Only at vertices whose BRDF is the same toward every direction (Lambert, or the report's
/// mix without a lobe), and never with the head-light (in the screen's and the store's L1, not in ln). The emitter
/// such a vertex's bounce direction meets then counts for nothing, as in L2.
///  - `store` (the store modes), asked first: a ready cell gives the light arriving there, times the vertex's
///    albedo, and no shadow ray is traced; where the cell is missing or not ready (or at a hit of the learning
///    share, l1_cache.h) the vertex traces its shadow ray as without a store, and the light that ray's sample brings
///    (without the BRDF or the MIS weight) feeds the cell as a one-sample record: feeding costs no ray. Where the
///    full store would refuse the cell, nothing is fed. At a path's first bounce hit q, where p was seen directly
///    (`bounces_before` 0) and q's BRDF is constant, the store is also asked for q's further light (l1_cache.h,
///    kFurtherMinSamples), in the cell L2 looked up at q when the path starts along L2's bounce: where it is ready
///    the path adds it times q's BRDF and ends; otherwise the path goes on and, where the cell may feed, its light
///    past q over its throughput there becomes a record.
///  - `screen` (the modes that read it): the pixel that sees the vertex directly gives its L1 (the report's reuse,
///    one bounce further); not with --reuse-diffuse-only or on a colour map.
struct FurtherBounceReuse {
  const Camera* camera = nullptr;
  const ScreenBuffer* screen = nullptr;
  const L1CacheAccess* store = nullptr;
};

/// ln's light, and where its vertices past q took their L1: the counts the reuse statistics add to L2's.
struct FurtherBounces {
  Vec3 light{0.0f};
  int lookups = 0;      ///< vertices past q that reflect light: each needs L1
  int from_screen = 0;  ///< of those, how many took it from the screen
  int from_store = 0;   ///< how many read it from a ready cell of the store
  int paths = 0;        ///< paths traced from p
  int ended_at_store = 0;  ///< of those, how many took their further light at q from the store and ended there
};

FurtherBounces estimate_further_bounces(const TracedScene& traced, const SurfacePoint& p,
                                        const RenderSettings& settings, int bounces_before, PixelSampler& sampler,
                                        uint64_t first_sample, uint64_t& rays_traced,
                                        const SharedBounce* shared = nullptr, int shared_count = 0,
                                        const FurtherBounceReuse& reuse = {});

}  // namespace lueur
