// The renderer's own rays per second against what the benchmark's ray arrays trace: how much of a frame is spent
// outside traversal (issue 18's "leaner frame"). Depends on the renderer and the benchmark scenes.
#pragma once

#include <cstdint>
#include <vector>

#include "bench/bench_rays.h"
#include "bench/bench_scenes.h"
#include "bench/bench_throughput.h"
#include "core/thread_pool.h"
#include "integrator/traced_scene.h"

namespace lueur::bench {

struct FrameFigures {
  int frames = 0;
  double seconds = 0.0;
  uint64_t primary = 0, bounce = 0, any_hit = 0;  ///< the rays the frames traced, by query
  double renderer_mrays = 0.0;                    ///< all of them over the frames' wall time
};

/// Renders whole frames of `traced` from `scene`'s view at `size` x `size` with the renderer's default settings
/// (Le, L1, L2; 16 + 16 rays; frame reuse; Sobol) on `pool`, until at least `seconds` and two frames have passed.
FrameFigures measure_frames(const TracedScene& traced, const BenchScene& scene, int size, ThreadPool& pool,
                            double seconds);

/// What the benchmark's arrays would take for the same rays: their count over the time that the measured
/// throughputs (Mrays/s of primary, bounce and shadow rays) give each kind.
double ray_mix_mrays(const FrameFigures& frames, double primary_mrays, double bounce_mrays, double shadow_mrays);

struct FrameComparison {
  FrameFigures frames;          ///< every round's frames together
  double renderer_mrays = 0.0;  ///< the median round's
  double arrays_mrays = 0.0;    ///< the median round's: the same mix of rays traced from the arrays
  double ratio = 0.0;           ///< the median of the rounds' ratios
  std::vector<double> ratios;   ///< each round's, in order
};

/// Alternates, `timing.rounds` times, the three ray arrays of `sets` through Lueur's BVH (`timing.seconds_per_round`
/// each) with the renderer's frames (`seconds` / rounds), and compares each round's frames with that round's arrays.
/// On a shared host a slow spell then slows both sides of a ratio; one measured before the other (as before session
/// 12) moved by 30% between two runs of the same build.
FrameComparison compare_frames_with_arrays(const BenchScene& scene, const Bvh& bvh, const RaySets& sets, int size,
                                           ThreadPool& pool, double seconds, const TimingOptions& timing);

}  // namespace lueur::bench
