// Timing the same ray arrays through Lueur's BVH and Embree, back to back, and timing their builds.
// Depends on the accelerator layer and the thread pool.
#pragma once

#include <optional>
#include <vector>

#include "accel/accelerator.h"
#include "core/thread_pool.h"

namespace lueur::bench {

enum class Query { kClosest, kAny };

/// Each figure is the median over alternating rounds. The best round was kept before session 8, but on a shared
/// host one lucky round could lift a ratio by 20% (1.07 against a median of 0.88 in one run); the median needs a
/// majority of rounds to move.
struct TimingOptions {
  double seconds_per_round = 0.3;  ///< each back-end traces whole arrays for at least this long per round
  int rounds = 5;                  ///< alternating rounds (lueur, embree, lueur, ...)
};

struct Throughput {
  double lueur = 0.0;            ///< Mrays/s, the median round
  std::optional<double> embree;  ///< absent without Embree
  double agreement = 1.0;        ///< share of rays with the same answer (triangle, or occluded or not)
};

/// Traces `rays` with both back-ends on `pool`, alternating lueur, embree, lueur, ... `embree` may be null.
/// Each back-end's figure is the median of its rounds (the mean of the middle two for an even count).
/// Embree is timed through rtcIntersect1 / rtcOccluded1 with its own t, u, v (embree_intersect_closest_raw).
Throughput measure_throughput(const std::vector<Ray>& rays, Query query, const Bvh& bvh, const EmbreeScene* embree,
                              ThreadPool& pool, const TimingOptions& options);

/// The median of `values` (the mean of the middle two for an even count; 0 for none).
double median(std::vector<double> values);

/// Build time and memory of both back-ends. Lueur's time runs from the corner array to the finished wide tree
/// (triangle preparation, BVH2 build, reinsertion, collapse); Embree's is rtcCommitScene alone, on a device, buffers
/// and geometry made beforehand, as Embree's users quote it.
struct BuildFigures {
  double lueur_ms = 0.0;
  std::optional<double> embree_ms;
  double lueur_bytes = 0.0;  ///< bytes per input triangle that the queries read (accelerator_bytes)
  std::optional<double> embree_bytes;
  double lueur_resident_bytes = 0.0;  ///< bytes per input triangle kept while tracing (accelerator_resident_bytes)
  std::optional<double> embree_resident_bytes;
};

/// Builds both back-ends `repeats` times, alternating, and keeps the fastest build of each; `bvh` and `embree`
/// receive the last.
BuildFigures measure_builds(const std::vector<Vec3>& corners, int repeats, Bvh& bvh,
                            std::shared_ptr<const EmbreeScene>& embree);

}  // namespace lueur::bench
