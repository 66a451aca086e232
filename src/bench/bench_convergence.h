// Time to quality on the default scene: the RMSE against a long reference render after equal time, for each
// light-sampling strategy and each L2 reuse mode. Depends on the renderer.
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "render/film.h"

namespace lueur::bench {

struct ConvergenceOptions {
  int width = 512, height = 512;
  int reference_frames = 128;  ///< frames of each reference render
  double seconds = 20.0;       ///< the equal time each variant gets (whole frames: it may run a little over)
  int threads = 0;             ///< 0: all
  uint64_t seed = 1;           ///< the variants' seed; references use another one, so their noise is independent
};

/// Root-mean-square difference over every pixel and channel of two images of the same size.
double image_rmse(const Image& a, const Image& b);

/// Runs every variant and its reference; returns one JSON object per variant. Progress goes to `log`.
nlohmann::ordered_json run_convergence(const ConvergenceOptions& options, std::FILE* log);

}  // namespace lueur::bench
