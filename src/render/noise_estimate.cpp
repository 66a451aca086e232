// The noise estimate from the film's power-of-two snapshots (the derivation is in the header).
#include "render/noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace lueur {
namespace {

using PassWeights = std::array<float, kPassCount>;

/// The relMSE's regulariser: errors on black pixels count as errors on a value of 0.1.
constexpr double kDenominatorFloor = 0.01;

/// The fitted exponent stays between independent sampling's 1 and a smooth 2D integrand's 3 under Owen scrambling.
constexpr double kMinExponent = 1.0, kMaxExponent = 3.0;

/// sum over passes of weight x sum / frames, per pixel channel; passes with weight 0 or without sums are left out.
template <typename PassSums>
std::vector<double> weighted_average(const PassSums& pass_sums, uint64_t frames, const PassWeights& weights,
                                     size_t values) {
  std::vector<double> average(values, 0.0);
  for (size_t p = 0; p < kPassCount; ++p) {
    const std::vector<float>& sum = pass_sums(p);
    if (weights[p] == 0.0f || sum.size() != values) continue;
    const double scale = static_cast<double>(weights[p]) / static_cast<double>(frames);
    for (size_t j = 0; j < values; ++j) average[j] += scale * static_cast<double>(sum[j]);
  }
  return average;
}

/// What the estimate of one weighted image is made of: the averages now and at the snapshots.
struct Averages {
  uint64_t frames = 0, newest = 0;  ///< the film's frame count, and the newest snapshot's (N)
  std::vector<double> now, at[kNoiseCheckpoints];
  bool older = false;   ///< whether the snapshot at N/4 is there
  bool oldest = false;  ///< whether the snapshot at N/8 is there
};

std::optional<Averages> averages_of(const Film& film, const PassWeights& weights, SamplerKind sampler) {
  const auto& checkpoints = film.checkpoints;
  const uint64_t needed = frames_before_noise_estimate(sampler);
  if (film.frames < needed || checkpoints[0].frames < needed || checkpoints[1].frames == 0) return std::nullopt;
  const size_t values = 3 * film.pixel_count();
  Averages a;
  a.frames = film.frames;
  a.newest = checkpoints[0].frames;
  a.now = weighted_average([&](size_t p) -> const std::vector<float>& { return film.sums[p]; }, film.frames, weights,
                           values);
  a.older = checkpoints[2].frames > 0;
  a.oldest = checkpoints[3].frames > 0;
  for (size_t c = 0; c < (a.oldest ? 4u : a.older ? 3u : 2u); ++c)
    a.at[c] = weighted_average([&](size_t p) -> const std::vector<float>& { return checkpoints[c].sums[p]; },
                               checkpoints[c].frames, weights, values);
  return a;
}

/// 1 / (ref^2 + 0.01) per pixel channel, with the current average standing in for the unknown ref. (A rare large
/// sample inflates its pixel's average and so shrinks that pixel's share of the estimate just where its error is
/// largest; the neighbourhood's median would resist it, but at the edge of a bright emitter it stands in a dark value
/// for a bright one and overstates the error a hundredfold, so the plain average it is.)
std::vector<double> inverse_denominators(const std::vector<double>& now) {
  std::vector<double> inverse(now.size());
  for (size_t j = 0; j < now.size(); ++j) inverse[j] = 1.0 / (now[j] * now[j] + kDenominatorFloor);
  return inverse;
}

/// The variance's decay exponent and the factor that turns a newest squared difference into V(F): V(F) =
/// (m_N - m_{N/2})^2 / (2^p - 1) x (N / F)^p.
struct Decay {
  double exponent = 1.0, factor = 1.0;
};
Decay decay_of(double exponent, const Averages& a) {
  return {exponent, std::pow(static_cast<double>(a.newest) / static_cast<double>(a.frames), exponent) /
                        (std::exp2(exponent) - 1.0)};
}

NoiseEstimate estimate_weighted(const Film& film, const PassWeights& weights, SamplerKind sampler) {
  const std::optional<Averages> a = averages_of(film, weights, sampler);
  if (!a) return {};
  const std::vector<double> inverse = inverse_denominators(a->now);
  double newest = 0.0, older = 0.0, oldest = 0.0;
  for (size_t j = 0; j < a->now.size(); ++j) {
    const double d = a->at[0][j] - a->at[1][j];
    newest += d * d * inverse[j];
    if (a->older) {
      const double e = a->at[1][j] - a->at[2][j];
      older += e * e * inverse[j];
    }
    if (a->oldest) {
      const double e = a->at[2][j] - a->at[3][j];
      oldest += e * e * inverse[j];
    }
  }
  // The exponent measured over the last halving and, where there are four snapshots, over the last two; either
  // alone is noisy enough to move the estimate by a third or more. The smaller one is kept: it gives the larger
  // error, so that a render stopped at a target noise errs on the side of being quieter than it says.
  double exponent = 1.0;
  if (sampler != SamplerKind::kIndependent && newest > 0.0 && older > 0.0) {
    exponent = std::log2(older / newest);
    if (oldest > 0.0) exponent = std::min(exponent, 0.5 * std::log2(oldest / newest));
    exponent = std::clamp(exponent, kMinExponent, kMaxExponent);
  }
  const Decay decay = decay_of(exponent, *a);
  // Independent frames: (m_{N/2} - m_{N/4})^2 estimates V(N/2) = 2 V(N) and (m_{N/4} - m_{N/8})^2 estimates 4 V(N),
  // each uncorrelated with the newest difference, so the mean of the three, so scaled, is the same estimate with
  // about a third of its variance. (Sobol frames fit their exponent from those differences: nothing is left to
  // average.)
  double differences = newest;
  if (sampler == SamplerKind::kIndependent) {
    int levels = 1;
    if (a->older) {
      differences += 0.5 * older;
      ++levels;
    }
    if (a->oldest) {
      differences += 0.25 * oldest;
      ++levels;
    }
    differences /= levels;
  }
  return {true, differences / static_cast<double>(a->now.size()) * decay.factor, exponent};
}

PassWeights one_pass(Pass pass) {
  PassWeights weights{};
  weights[static_cast<size_t>(pass)] = 1.0f;
  return weights;
}

PassWeights enabled_weights(const std::array<bool, kPassCount>& enabled, const PassWeights& weights) {
  PassWeights w{};
  for (size_t p = 0; p < kPassCount; ++p) w[p] = enabled[p] ? weights[p] : 0.0f;
  return w;
}

}  // namespace

uint64_t frames_before_noise_estimate(SamplerKind sampler) {
  // Independent frames need one difference (N = 2); the Sobol sampler's exponent needs two (N = 4).
  return sampler == SamplerKind::kIndependent ? 2 : 4;
}

NoiseEstimate estimate_pass_noise(const Film& film, Pass pass, SamplerKind sampler) {
  if (!film.has(pass)) return {};
  return estimate_weighted(film, one_pass(pass), sampler);
}

NoiseEstimate estimate_image_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                                   const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  return estimate_weighted(film, enabled_weights(enabled, weights), sampler);
}

FilmNoise estimate_film_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                              const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  FilmNoise noise;
  for (int p = 0; p < kPassCount; ++p)
    noise.passes[static_cast<size_t>(p)] = estimate_pass_noise(film, static_cast<Pass>(p), sampler);
  noise.image = estimate_image_noise(film, enabled, weights, sampler);
  return noise;
}

Image pixel_noise_map(const Film& film, const std::array<bool, kPassCount>& enabled,
                      const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  const NoiseEstimate image = estimate_image_noise(film, enabled, weights, sampler);
  if (!image.known) return {};
  const std::optional<Averages> a = averages_of(film, enabled_weights(enabled, weights), sampler);
  const Decay decay = decay_of(image.exponent, *a);
  // Each pixel's relMSE from both differences where the older one is there: (m_{N/2} - m_{N/4})^2 estimates
  // 2^p (2^p - 1) V(N), so scaled by 2^-p it is a second estimate of what the newest difference estimates.
  const int width = film.width, height = film.height;
  std::vector<double> per_pixel(film.pixel_count(), 0.0);
  const std::vector<double> inverse = inverse_denominators(a->now);
  const double older_scale = std::exp2(-image.exponent);
  for (size_t i = 0; i < per_pixel.size(); ++i) {
    double sum = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      const size_t j = 3 * i + c;
      const double d = a->at[0][j] - a->at[1][j];
      double squared = d * d;
      if (a->older) {
        const double e = a->at[1][j] - a->at[2][j];
        squared = 0.5 * (squared + e * e * older_scale);
      }
      sum += squared * inverse[j];
    }
    per_pixel[i] = sum / 3.0 * decay.factor;
  }
  Image map{width, height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double sum = 0.0;
      int count = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= width || v >= height) continue;
          sum += per_pixel[static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u)];
          ++count;
        }
      const float error = static_cast<float>(std::sqrt(sum / count));
      const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
      map.rgb[i] = map.rgb[i + 1] = map.rgb[i + 2] = error;
    }
  return map;
}

}  // namespace lueur
