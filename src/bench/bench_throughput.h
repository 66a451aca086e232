// Timing the same ray arrays through Lueur's BVH and Embree, back to back, and timing their builds.
// Depends on the accelerator layer and the thread pool.
#pragma once

#include <optional>
#include <vector>

#include "accel/accelerator.h"
#include "render/thread_pool.h"

namespace lueur::bench {

enum class Query { kClosest, kAny };

struct TimingOptions {
  double seconds_per_round = 0.5;  ///< each back-end traces whole arrays for at least this long per round
  int rounds = 3;                  ///< alternating rounds; the best of each back-end is kept (least disturbed)
};

struct Throughput {
  double lueur = 0.0;            ///< Mrays/s
  std::optional<double> embree;  ///< absent without Embree
  double agreement = 1.0;        ///< share of rays with the same answer (triangle, or occluded or not)
};

/// Traces `rays` with both back-ends on `pool`, alternating lueur, embree, lueur, ... `embree` may be null.
/// Embree is timed through rtcIntersect1 / rtcOccluded1 with its own t, u, v (embree_intersect_closest_raw).
Throughput measure_throughput(const std::vector<Ray>& rays, Query query, const Bvh& bvh, const EmbreeScene* embree,
                              ThreadPool& pool, const TimingOptions& options);

struct BuildFigures {
  double lueur_ms = 0.0;
  std::optional<double> embree_ms;
  double lueur_bytes = 0.0;  ///< bytes per input triangle
  std::optional<double> embree_bytes;
};

/// Builds both back-ends `repeats` times and keeps the fastest build of each; `bvh` and `embree` receive the last.
BuildFigures measure_builds(const std::vector<Vec3>& corners, int repeats, Bvh& bvh,
                            std::shared_ptr<const EmbreeScene>& embree);

}  // namespace lueur::bench
