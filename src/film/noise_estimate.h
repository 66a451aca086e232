// How noisy the running averages are, estimated from the film alone, without a reference: for each pass and for the
// weighted combination, as the relMSE of issue 8 (mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01)),
// with the current average standing in for the unknown ref in the denominator.
//
// The film keeps its pass sums at the last four powers of two of its frame count: N, N/2, N/4 and N/8. The first N
// frames are two halves of N/2 frames, each distributed as an N/2-frame render (for the Sobol sampler each half is an
// aligned block of the sequence, itself a net), so with V(n) the variance of an n-frame average,
//   D(N) = E[(m_N - m_{N/2})^2] = V(N/2) - V(N),
// whatever the correlation between the halves; the snapshots give D(N), D(N/2) and D(N/4). Independent frames have
// V(n) = V(1) / n, so D(N) = V(N). Low-discrepancy frames fall faster while they resolve the integrand, then slow
// down toward 1 / n (where the padded dimensions interact, and at discontinuities): the local exponent keeps
// changing, and one exponent fitted over the last halvings lags it (measured: 0.6x the true error after 16 frames of
// the default settings). So V(n) is fitted as a mixture of rates, sum over k of c_k n^-k for k = 1, 2, 3 with
// c_k >= 0, whose differences D(n) = sum c_k n^-k (2^k - 1) match the observed ones; between powers of two the same
// mixture carries the estimate to the current frame count.
// The estimate sees noise only: a bias (the L1 store's, screen reuse's) is invisible to it. Depends on the film.
#pragma once

#include <array>

#include "film/film.h"
#include "passes/render_settings.h"

namespace lueur {

/// How the relMSE of an n-frame average falls with n: sum over k = 1, 2, 3 of `weights[k - 1]` x (n / frames)^-k.
struct VarianceDecay {
  double frames = 1.0;              ///< the frame count the weights are relative to
  std::array<double, 3> weights{};  ///< of the rates 1 / n, 1 / n^2 and 1 / n^3, all >= 0
  double at(double n) const;
  /// -d log V / d log n at n: how fast the variance falls there (1 for independent frames).
  double exponent_at(double n) const;
};

struct NoiseEstimate {
  bool known = false;     ///< false until the film holds the snapshots the estimate needs
  double rel_mse = 0.0;   ///< the running average's estimated relMSE
  double exponent = 1.0;  ///< how fast its variance falls now: as frames^-exponent (1 for independent frames)
  VarianceDecay decay;    ///< the fitted fall, which gives rel_mse at the film's frame count and carries it on
};

/// Fits the decay to squared half-differences, relMSE-scaled: `differences[i]` is D(newest_frames / 2^i) (0 where
/// it is not known), for `count` levels. Least squares on the relative residuals, each older level weighing half the
/// one after it, over every subset of the three rates whose weights come out non-negative.
VarianceDecay fit_variance_decay(uint64_t newest_frames, const double* differences, int count);

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
/// decay: a full estimate reads the whole film five times over, too much to do for every frame of a large image
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
