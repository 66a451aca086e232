// Time to quality on the default scene: the RMSE against a long reference render after equal time, for each
// light-sampling strategy and each L2 reuse mode. Depends on the renderer.
#pragma once

#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "film/film.h"

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

/// The mean over all channels of (a - b)^2.
double image_mse(const Image& a, const Image& b);

/// A reference made of two independent renders: their mean, and its own noise (the variance of the mean, a
/// quarter of their mean squared difference), to take out of errors measured against it: E[(x - r)^2] = e(x)^2 +
/// var(r) for an x independent of r.
struct TwoRenderReference {
  Image mean;
  double noise = 0.0;
};
TwoRenderReference reference_of_two(const Image& a, const Image& b);

/// Issue 8's relative error of `image` against `reference`: the mean over every pixel and channel of
/// (x - ref)^2 / (ref^2 + 0.01). Unlike the RMSE, a few bright pixels (an emitter's anti-aliased edge, whose Le
/// varies by its whole radiance from frame to frame) cannot outweigh the rest of the image.
double image_relmse(const Image& image, const Image& reference);

/// Runs every variant and its reference; returns one JSON object per variant. Progress goes to `log`.
nlohmann::ordered_json run_convergence(const ConvergenceOptions& options, std::FILE* log);

}  // namespace lueur::bench
