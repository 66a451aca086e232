// How noisy the running averages are, estimated from the film alone, without a reference: for each pass and for the
// weighted combination, as the relMSE of issue 8 (mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01)),
// with the current average standing in for the unknown ref in the denominator.
//
// The film keeps its pass sums at the last four powers of two of its frame count: N, N/2, N/4 and N/8. The first N
// frames are two halves of N/2 frames, each distributed as an N/2-frame render (for the Sobol sampler each half is an
// aligned block of the sequence, itself a net), so with V(n) the variance of an n-frame average,
//   E[(m_N - m_{N/2})^2] = V(N/2) - V(N),
// whatever the correlation between the halves. If V(n) falls as n^-p, that is (2^p - 1) V(N). Independent frames
// have p = 1; low-discrepancy frames converge faster, and their p is measured from the differences the snapshots
// give: (V(N/8) - V(N/4)) / (V(N/2) - V(N)) = 4^p. Between checkpoints, V(F) = V(N) (N/F)^p.
// The estimate sees noise only: a bias (the L1 store's, screen reuse's) is invisible to it. Depends on the film.
#pragma once

#include <array>

#include "render/film.h"
#include "render/settings.h"

namespace lueur {

struct NoiseEstimate {
  bool known = false;     ///< false until the film holds the snapshots the estimate needs
  double rel_mse = 0.0;   ///< the running average's estimated relMSE
  double exponent = 1.0;  ///< how fast its variance falls: as frames^-exponent (1 for independent frames)
};

/// The frames a film needs before its noise can be estimated with this sampler.
uint64_t frames_before_noise_estimate(SamplerKind sampler);

/// The noise of one pass's running average.
NoiseEstimate estimate_pass_noise(const Film& film, Pass pass, SamplerKind sampler);

/// The noise of the image sum over enabled passes of weight x average(pass).
NoiseEstimate estimate_image_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                                   const std::array<float, kPassCount>& weights, SamplerKind sampler);

/// Every rendered pass's estimate and the combined image's.
struct FilmNoise {
  std::array<NoiseEstimate, kPassCount> passes;  ///< unknown for passes not rendered
  NoiseEstimate image;
};
FilmNoise estimate_film_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                              const std::array<float, kPassCount>& weights, SamplerKind sampler);

/// The estimate of a film that keeps accumulating, remade only when its snapshots, the weights or the sampler change
/// (at powers of two of the frame count) and carried in between to the current frame count along the fitted
/// exponent: a full estimate reads the whole film five times over, too much to do for every frame of a large image
/// on the display's thread.
class RunningNoiseEstimate {
 public:
  const FilmNoise& update(const Film& film, const std::array<bool, kPassCount>& enabled,
                          const std::array<float, kPassCount>& weights, SamplerKind sampler);
  void reset() { made_ = false; }

 private:
  bool made_ = false;
  uint64_t made_at_ = 0, snapshot_frames_ = 0;
  std::array<bool, kPassCount> enabled_{};
  std::array<float, kPassCount> weights_{};
  SamplerKind sampler_ = SamplerKind::kSobol;
  FilmNoise made_noise_, noise_;
};

/// Each pixel's estimated relative error (the square root of its relMSE, its channels averaged) in the combined
/// image, smoothed over 3 x 3 pixels so that the one-pixel estimates read as a map; an empty image while unknown.
Image pixel_noise_map(const Film& film, const std::array<bool, kPassCount>& enabled,
                      const std::array<float, kPassCount>& weights, SamplerKind sampler);

}  // namespace lueur
