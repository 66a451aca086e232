// The ray arrays the benchmark traces through both back-ends: primary camera rays, shadow rays from the primary
// hits to points on the lights, and cosine-distributed bounce rays from the primary hits. Depends on the
// accelerator, camera and scene layers.
#pragma once

#include <vector>

#include "accel/accelerator.h"
#include "bench/bench_scenes.h"

namespace lueur::bench {

struct RaySets {
  std::vector<Ray> primary;  ///< one jittered ray per pixel, in 16 x 16 tiles like the renderer
  std::vector<Ray> shadow;   ///< one per primary hit that faces a light sample (finite tmax, any-hit query)
  std::vector<Ray> bounce;   ///< one per primary hit (closest-hit query)
};

/// Rays for a width x height view of `scene`, a pure function of the seed; `accel` finds the primary hits.
RaySets make_ray_sets(const BenchScene& scene, const Accelerator& accel, int width, int height, uint64_t seed);

}  // namespace lueur::bench
