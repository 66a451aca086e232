// The renderer's own rays per second against what the benchmark's ray arrays trace: how much of a frame is spent
// outside traversal (issue 18's "leaner frame"). Depends on the renderer and the benchmark scenes.
#pragma once

#include <cstdint>

#include "bench/bench_scenes.h"
#include "render/thread_pool.h"

namespace lueur::bench {

struct FrameFigures {
  int frames = 0;
  double seconds = 0.0;
  uint64_t primary = 0, bounce = 0, any_hit = 0;  ///< the rays the frames traced, by query
  double renderer_mrays = 0.0;                    ///< all of them over the frames' wall time
};

/// Renders whole frames of `scene` from its view at `size` x `size` with the renderer's default settings (Le, L1,
/// L2; 16 + 16 rays; frame reuse; Sobol) on `pool`, until at least `seconds` and two frames have passed.
FrameFigures measure_frames(const BenchScene& scene, int size, ThreadPool& pool, double seconds);

/// What the benchmark's arrays would take for the same rays: their count over the time that the measured
/// throughputs (Mrays/s of primary, bounce and shadow rays) give each kind.
double ray_mix_mrays(const FrameFigures& frames, double primary_mrays, double bounce_mrays, double shadow_mrays);

}  // namespace lueur::bench
