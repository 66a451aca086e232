// Renders frames into a Film: tiles fanned out over a thread pool, each pixel traced with its own random streams,
// so the result is the same bytes for any thread count.
// This folder, integrator/, holds the estimators of the report's passes (camera rays and Le, L1's shadow rays, L2's
// bounce rays and their reuse of L1, AO), the BRDF, the head-light and the scene as the tracer sees it; it sits on
// light choice (lights/), the L1 store (store/) and the film (film/), and never sees GL.
#pragma once

#include <atomic>
#include <cstdint>

#include "core/camera.h"
#include "film/film.h"
#include "store/l1_cache.h"
#include "passes/render_settings.h"
#include "core/thread_pool.h"
#include "integrator/traced_scene.h"

namespace lueur {

inline constexpr int kTileSize = 16;

struct FrameResult {
  uint64_t rays = 0;             ///< primary + shadow + bounce rays traced in this frame
  uint64_t primary_rays = 0;     ///< of those, camera rays (closest hit)
  uint64_t bounce_rays = 0;      ///< L2 bounce rays (closest hit); the rest are any-hit (shadow and AO) rays
  uint64_t l2_bounce_hits = 0;   ///< L2 bounce rays that hit a surface
  uint64_t l2_reused = 0;        ///< of those, how many reused L1 from the screen
  uint64_t l2_cached = 0;        ///< of those, how many took L1 from the L1 store
  uint64_t ln_lookups = 0;       ///< ln's vertices past q that needed L1 (further_bounces.h)
  uint64_t ln_reused = 0;        ///< of those, how many took it from the screen
  uint64_t ln_cached = 0;        ///< of those, how many read it from the L1 store
  uint64_t ln_paths = 0;         ///< ln's paths (with L2: those that start along L2's bounces)
  uint64_t ln_ended = 0;         ///< of those, how many took their further light from the store at q and ended
  L1CacheStats cache;            ///< the L1 store after this frame's merge (empty without a store mode)
  ServedSamples served_samples;  ///< the samples of the store's cells that served this frame's hits
  double l2_seconds = 0.0;       ///< wall time of the second phase: L2, and ln when it is on
  bool completed = true;         ///< false when `cancel` stopped it early (the film is then left untouched)
  uint64_t dropped_samples = 0;  ///< pixel values not added to the film: not finite, or too large for the film
};

/// The unit of a film of this scene (Film::unit): 2^-32 of its brightest emission (the head-light's too, when it is
/// on), rounded up to a power of two, and at least 2^-32.
double film_unit(const TracedScene& traced, const Camera& camera, const RenderSettings& settings);

/// The room the L1 store gets for these settings (L1Cache::reset): the --cache-mb cap where L2 takes L1(q) from the
/// store, else none.
uint64_t l1_store_bytes(const RenderSettings& settings);

/// How many frames these settings can accumulate before an estimator's sample index passes 2^32, where a pixel's
/// sample sequence starts over (core/pixel_sampler.h) and further frames would repeat earlier ones: 2^32 over the
/// longest run of samples one frame takes of any sampler. A pass's run is its rays per frame rounded up to a power
/// of two (first_sample_of_run); L2's recomputed L1(q) takes, per frame, a run of shadow samples for each of its
/// bounce rays: the two counts multiply.
uint64_t frames_before_samples_repeat(const RenderSettings& settings);

/// What a render accumulates over its frames: the film's pixel sums and, beside them, the world-space L1 store that
/// the integrator learns from the same frames (store modes only). Reset together; the resume state holds both.
struct Accumulation {
  Film film;
  L1Cache store;  ///< empty, with no room, unless the settings' reuse mode uses it
  /// Sizes the film for these settings and gives the store its room (none without a store mode); clears both.
  void reset(const RenderSettings& settings) {
    film.reset(settings);
    store.reset(l1_store_bytes(settings));
  }
};

/// `screen+cache` reads the screen in a render's first frames only, while the store is young (its first two
/// generations); from this frame on it renders as `cache`. The screen's reuse has a spatial bias that does not
/// shrink with the frames, and the store, emptied at the start of every generation, would lean on it again at each:
/// measured at 64x64 on the default scene (lueur-bench --sections store-frames), L2's error rose between frames
/// 2048 and 4096. The screen's part of the image then fades as 1 / frames.
inline constexpr uint64_t kScreenCacheFrames = 32;

/// Traces frame number `film.frames` at full resolution and adds it to the film's sums (choosing the film's unit if
/// it has none yet). `store` is the world-space L1 store that the store modes read and feed, kept by the caller
/// beside the film across frames (reset with l1_store_bytes); it may be null where the settings do not use one, and
/// a store mode without one is a std::invalid_argument.
/// `cancel`, when given and set, makes workers drop their remaining tiles.
FrameResult render_frame(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, Film& film,
                         L1Cache* store, ThreadPool& pool, const std::atomic<bool>* cancel = nullptr);
inline FrameResult render_frame(const TracedScene& traced, const Camera& camera, const RenderSettings& settings,
                                Accumulation& into, ThreadPool& pool, const std::atomic<bool>* cancel = nullptr) {
  return render_frame(traced, camera, settings, into.film, &into.store, pool, cancel);
}

}  // namespace lueur
