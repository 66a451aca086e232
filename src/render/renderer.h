// Renders frames into a Film: tiles fanned out over a thread pool, each pixel traced with its own random streams,
// so the result is the same bytes for any thread count. Depends on the render layer below it.
#pragma once

#include <atomic>
#include <cstdint>

#include "render/camera.h"
#include "render/film.h"
#include "render/settings.h"
#include "render/thread_pool.h"
#include "render/traced_scene.h"

namespace lueur {

inline constexpr int kTileSize = 16;

struct FrameResult {
  uint64_t rays = 0;             ///< primary + shadow + bounce rays traced in this frame
  uint64_t primary_rays = 0;     ///< of those, camera rays (closest hit)
  uint64_t bounce_rays = 0;      ///< L2 bounce rays (closest hit); the rest are any-hit (shadow and AO) rays
  uint64_t l2_bounce_hits = 0;   ///< L2 bounce rays that hit a surface
  uint64_t l2_reused = 0;        ///< of those, how many reused L1 from the screen
  uint64_t l2_cached = 0;        ///< of those, how many took L1 from the L1 store
  L1CacheStats cache;            ///< the L1 store after this frame's merge (empty without a store mode)
  double l2_seconds = 0.0;       ///< wall time of the L2 phase
  bool completed = true;         ///< false when `cancel` stopped it early (the film is then left untouched)
  uint64_t dropped_samples = 0;  ///< pixel values not added to the film: not finite, or too large for the film
};

/// The unit of a film of this scene (Film::unit): 2^-32 of its brightest emission (the head-light's too, when it is
/// on), rounded up to a power of two, and at least 2^-32.
double film_unit(const TracedScene& traced, const Camera& camera, const RenderSettings& settings);

/// Traces frame number `film.frames` at full resolution and adds it to the film's sums (choosing the film's unit if
/// it has none yet).
/// `cancel`, when given and set, makes workers drop their remaining tiles.
FrameResult render_frame(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, Film& film,
                         ThreadPool& pool, const std::atomic<bool>* cancel = nullptr);

}  // namespace lueur
