// L2: one-bounce indirect light with the report's screen-space reuse of L1, and AO, its cheap stand-in.
// Depends on the traced scene, the camera and the direct-light estimator.
#pragma once

#include <vector>

#include "core/pixel_sampler.h"
#include "core/camera.h"
#include "store/l1_cache.h"
#include "passes/render_settings.h"
#include "integrator/traced_scene.h"

namespace lueur {

/// What one pixel's primary ray hit, beside its triangle: read only once the triangle matches.
struct ScreenPixel {
  Vec3 position{0.0f};
  Vec3 l1{0.0f};      ///< this frame's L1 toward the camera (diffuse part only with reuse_diffuse_only)
  Vec3 albedo{0.0f};  ///< the diffuse albedo at `position`: a bounce hit beside it on a colour map rescales l1
};

/// What the primary rays of the current frame saw: the screen that L2 reuses. The triangles have an array of their
/// own: most lookups stop at them, and 4 bytes a pixel stay in cache where the whole record would not.
struct ScreenBuffer {
  int width = 0, height = 0;
  std::vector<uint32_t> triangle;  ///< kNoHit where the pixel sees nothing
  std::vector<ScreenPixel> pixels;
  std::vector<Vec3> l1_average;  ///< running L1 average including this frame (reuse = average only)
  void resize(int w, int h);
  /// The L1 a bounce hit on pixel `i`'s surface takes under `reuse` (a mode that reads the screen).
  const Vec3& reused_l1(size_t i, ReuseMode reuse) const {
    return reuse == ReuseMode::kAverage ? l1_average[i] : pixels[i].l1;
  }
};

struct IndirectResult {
  Vec3 l2{0.0f};
  Vec3 from_reused{0.0f};      ///< the part of l2 whose L1(q) came from the screen (report figure 7)
  Vec3 from_recomputed{0.0f};  ///< the part whose L1(q) was traced anew (report figure 8)
  int bounce_rays = 0;         ///< bounce rays traced
  int bounce_hits = 0;         ///< bounce rays that hit a surface that reflects light (a light's own: not counted)
  int reused = 0;              ///< of those, how many took L1 from the screen
  Vec3 from_cached{0.0f};      ///< the part whose L1(q) came from the L1 store
  int cached = 0;              ///< bounce hits that took L1 from the store
};

/// One of L2's bounce rays as it left p and what it met: where ln's path of the same index starts (its first
/// segment shared, not traced twice).
struct SharedBounce {
  bool open = false;  ///< false: the direction dipped below p's surface and was not traced
  Ray ray;
  Hit hit;  ///< not found(): the ray met nothing
  /// With the store: L2 looked up q's jittered cell, whose key ln's path then looks up again (its slot is still in
  /// the cache) rather than drawing a cell of its own.
  bool keyed = false;
  L1CacheKey key;
  uint64_t hash = 0;
};

/// The screen pixel whose primary ray hit q, or -1: q projects into it, its primary ray hit q's triangle, and its
/// hit lies within 1.5 pixel footprints of q, measured on the triangle's plane (`q_normal`: its normal, of any length).
int find_reusable_pixel(const Camera& camera, const ScreenBuffer& screen, uint32_t triangle, const Vec3& q,
                        const Vec3& q_normal);

/// L2 at `sp` with settings.l2_rays cosine-weighted rays (Dutré formula 35), samples `first_sample` onwards of
/// `bounce_sampler`. Where a ray hits q, L1(q) toward p is taken from the pixel q projects to when that pixel's
/// primary ray hit q (find_reusable_pixel), otherwise recomputed with settings.recompute_rays() shadow rays, drawn
/// from `recompute_sampler` (bounce b's shadow rays are its samples b x recompute_rays onwards). Emission at q is
/// not added: it is already L1 at p. With `cache` (the store modes), a hit the screen did not serve looks up its
/// jittered cell: a cell with kL1CacheMinSamples samples gives the constant part of L1(q) (the rest of the BRDF is
/// traced toward p, as --reuse-diffuse-only does), except at the learning share of its hits (use_of_store); otherwise
/// L1(q) is recomputed with kL1CacheFillRays rays and its arriving light becomes a record for the store, or, where
/// the cell is missing and the store full there
/// (L1Cache::refuses_new_cell), with recompute_rays and no record (bounce b's shadow rays are its samples b x
/// max(recompute_rays, kL1CacheFillRays) onwards).
/// `shared[k]` receives bounce k's ray and hit for k < `shared_count` (at most kSampleBatch and l2_rays): the
/// first segments of ln's paths.
IndirectResult estimate_indirect_light(const TracedScene& traced, const Camera& camera, const ScreenBuffer& screen,
                                       const SurfacePoint& sp, const RenderSettings& settings,
                                       PixelSampler& bounce_sampler, PixelSampler& recompute_sampler,
                                       uint64_t first_sample, uint64_t& rays_traced,
                                       const L1CacheAccess* cache = nullptr, SharedBounce* shared = nullptr,
                                       int shared_count = 0);

/// Ambient occlusion: Kd times the fraction of `rays` cosine rays (samples `first_sample` onwards) that travel
/// farther than `radius`, the light of a uniform white sky that nearby geometry blocks.
Vec3 estimate_ambient_occlusion(const TracedScene& traced, const SurfacePoint& sp, int rays, float radius,
                                PixelSampler& sampler, uint64_t first_sample, uint64_t& rays_traced);

/// The AO radius in world units for these settings (a tenth of the scene diagonal by default).
float ambient_occlusion_radius(const TracedScene& traced, const RenderSettings& settings);

}  // namespace lueur
