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

/// What the estimate reads of the film: its pass sums now and at the snapshots, with their frame counts.
struct Snapshots {
  int levels = 0;                                     ///< snapshots present: 2 (N, N/2), 3 (and N/4) or 4 (and N/8)
  double inverse_frames[1 + kNoiseCheckpoints] = {};  ///< now, then each snapshot
  /// Per pass, its sums now and at each snapshot; null for a pass not rendered.
  const float* sums[kPassCount][1 + kNoiseCheckpoints] = {};

  /// Every pass's averages at pixel channel `j`: now (`at[p][0]`) and at each snapshot (`at[p][1 + c]`).
  void pass_averages(size_t j, double (&at)[kPassCount][1 + kNoiseCheckpoints]) const {
    for (size_t p = 0; p < kPassCount; ++p) {
      if (!sums[p][0]) continue;
      for (int c = 0; c <= levels; ++c) at[p][c] = static_cast<double>(sums[p][c][j]) * inverse_frames[c];
    }
  }

  /// The weighted image's averages at pixel channel `j`, from every pass's.
  void image_averages(const double (&passes)[kPassCount][1 + kNoiseCheckpoints], const PassWeights& weights,
                      double* at) const {
    for (int c = 0; c <= levels; ++c) at[c] = 0.0;
    for (size_t p = 0; p < kPassCount; ++p) {
      if (weights[p] == 0.0f || !sums[p][0]) continue;
      const double w = static_cast<double>(weights[p]);
      for (int c = 0; c <= levels; ++c) at[c] += w * passes[p][c];
    }
  }
};

std::optional<Snapshots> snapshots_of(const Film& film, SamplerKind sampler) {
  const auto& checkpoints = film.checkpoints;
  const uint64_t needed = frames_before_noise_estimate(sampler);
  if (film.frames < needed || checkpoints[0].frames < needed || checkpoints[1].frames == 0) return std::nullopt;
  Snapshots s;
  s.inverse_frames[0] = 1.0 / static_cast<double>(film.frames);
  while (s.levels < kNoiseCheckpoints && checkpoints[static_cast<size_t>(s.levels)].frames > 0) {
    s.inverse_frames[1 + s.levels] = 1.0 / static_cast<double>(checkpoints[static_cast<size_t>(s.levels)].frames);
    ++s.levels;
  }
  for (size_t p = 0; p < kPassCount; ++p) {
    if (film.sums[p].empty()) continue;
    // The film is reset as a whole, so a rendered pass has every snapshot; sizes are checked all the same, so that
    // nothing is ever read out of bounds.
    for (int c = 0; c < s.levels; ++c)
      if (checkpoints[static_cast<size_t>(c)].sums[p].size() != film.sums[p].size()) return std::nullopt;
    s.sums[p][0] = film.sums[p].data();
    for (int c = 0; c < s.levels; ++c) s.sums[p][1 + c] = checkpoints[static_cast<size_t>(c)].sums[p].data();
  }
  return s;
}

/// 1 / (ref^2 + 0.01) for a pixel channel, with the current average standing in for the unknown ref. (A rare large
/// sample inflates its pixel's average and so shrinks that pixel's share of the estimate just where its error is
/// largest; the neighbourhood's median would resist it, but at the edge of a bright emitter it stands in a dark value
/// for a bright one and overstates the error a hundredfold, so the plain average it is.)
double inverse_denominator(double now) { return 1.0 / (now * now + kDenominatorFloor); }

/// The squared half-differences of one weighted image over its denominators, summed over the pixel channels:
/// (m_N - m_{N/2})^2, (m_{N/2} - m_{N/4})^2 and (m_{N/4} - m_{N/8})^2.
struct Differences {
  double newest = 0.0, older = 0.0, oldest = 0.0;
  void add(const double* at, int levels) {
    const double inverse = inverse_denominator(at[0]);
    const double d = at[1] - at[2];
    newest += d * d * inverse;
    if (levels > 2) {
      const double e = at[2] - at[3];
      older += e * e * inverse;
    }
    if (levels > 3) {
      const double e = at[3] - at[4];
      oldest += e * e * inverse;
    }
  }
};

/// The variance's decay exponent and the factor that turns a newest squared difference into V(F): V(F) =
/// (m_N - m_{N/2})^2 / (2^p - 1) x (N / F)^p.
struct Decay {
  double exponent = 1.0, factor = 1.0;
};
Decay decay_of(double exponent, const Film& film) {
  const double newest = static_cast<double>(film.checkpoints[0].frames), now = static_cast<double>(film.frames);
  return {exponent, std::pow(newest / now, exponent) / (std::exp2(exponent) - 1.0)};
}

NoiseEstimate estimate_from(const Differences& sums, const Film& film, SamplerKind sampler) {
  // The exponent measured over the last halving and, where there are four snapshots, over the last two; either
  // alone is noisy enough to move the estimate by a third or more. The smaller one is kept: it gives the larger
  // error, so that a render stopped at a target noise errs on the side of being quieter than it says.
  double exponent = 1.0;
  if (sampler != SamplerKind::kIndependent && sums.newest > 0.0 && sums.older > 0.0) {
    exponent = std::log2(sums.older / sums.newest);
    if (sums.oldest > 0.0) exponent = std::min(exponent, 0.5 * std::log2(sums.oldest / sums.newest));
    exponent = std::clamp(exponent, kMinExponent, kMaxExponent);
  }
  // Independent frames: (m_{N/2} - m_{N/4})^2 estimates V(N/2) = 2 V(N) and (m_{N/4} - m_{N/8})^2 estimates 4 V(N),
  // each uncorrelated with the newest difference, so the mean of the three, so scaled, is the same estimate with
  // about a third of its variance. (Sobol frames fit their exponent from those differences: nothing is left to
  // average.)
  double differences = sums.newest;
  if (sampler == SamplerKind::kIndependent) {
    int levels = 1;
    if (film.checkpoints[2].frames > 0) {
      differences += 0.5 * sums.older;
      ++levels;
    }
    if (film.checkpoints[3].frames > 0) {
      differences += 0.25 * sums.oldest;
      ++levels;
    }
    differences /= levels;
  }
  const double values = 3.0 * static_cast<double>(film.pixel_count());
  return {true, differences / values * decay_of(exponent, film).factor, exponent};
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

FilmNoise estimate_film_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                              const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  FilmNoise noise;
  const std::optional<Snapshots> s = snapshots_of(film, sampler);
  if (!s) return noise;
  // One sweep over the film for every pass and the combination: each value is read once.
  const PassWeights image_weights = enabled_weights(enabled, weights);
  std::array<Differences, kPassCount> passes;
  Differences image;
  const size_t values = 3 * film.pixel_count();
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  double at[1 + kNoiseCheckpoints];
  for (size_t j = 0; j < values; ++j) {
    s->pass_averages(j, passes_at);
    for (size_t p = 0; p < kPassCount; ++p)
      if (!film.sums[p].empty()) passes[p].add(passes_at[p], s->levels);
    s->image_averages(passes_at, image_weights, at);
    image.add(at, s->levels);
  }
  for (size_t p = 0; p < kPassCount; ++p)
    if (!film.sums[p].empty()) noise.passes[p] = estimate_from(passes[p], film, sampler);
  noise.image = estimate_from(image, film, sampler);
  return noise;
}

NoiseEstimate estimate_pass_noise(const Film& film, Pass pass, SamplerKind sampler) {
  if (!film.has(pass)) return {};
  return estimate_film_noise(film, {}, {}, sampler).passes[static_cast<size_t>(pass)];
}

NoiseEstimate estimate_image_noise(const Film& film, const std::array<bool, kPassCount>& enabled,
                                   const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  const std::optional<Snapshots> s = snapshots_of(film, sampler);
  if (!s) return {};
  const PassWeights image_weights = enabled_weights(enabled, weights);
  Differences image;
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  double at[1 + kNoiseCheckpoints];
  for (size_t j = 0; j < 3 * film.pixel_count(); ++j) {
    s->pass_averages(j, passes_at);
    s->image_averages(passes_at, image_weights, at);
    image.add(at, s->levels);
  }
  return estimate_from(image, film, sampler);
}

const FilmNoise& RunningNoiseEstimate::update(const Film& film, const std::array<bool, kPassCount>& enabled,
                                              const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  const uint64_t snapshot_frames = film.checkpoints[0].frames;
  if (!made_ || film.frames < made_at_ || snapshot_frames != snapshot_frames_ || enabled != enabled_ ||
      weights != weights_ || sampler != sampler_) {
    made_noise_ = estimate_film_noise(film, enabled, weights, sampler);
    made_ = true;
    made_at_ = film.frames;
    snapshot_frames_ = snapshot_frames;
    enabled_ = enabled;
    weights_ = weights;
    sampler_ = sampler;
  }
  noise_ = made_noise_;
  const auto carry = [&](NoiseEstimate& e) {
    if (e.known && film.frames > made_at_)
      e.rel_mse *= std::pow(static_cast<double>(made_at_) / static_cast<double>(film.frames), e.exponent);
  };
  for (NoiseEstimate& e : noise_.passes) carry(e);
  carry(noise_.image);
  return noise_;
}

Image pixel_noise_map(const Film& film, const std::array<bool, kPassCount>& enabled,
                      const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  const NoiseEstimate image = estimate_image_noise(film, enabled, weights, sampler);
  if (!image.known) return {};
  const std::optional<Snapshots> s = snapshots_of(film, sampler);
  const double factor = decay_of(image.exponent, film).factor;
  const PassWeights image_weights = enabled_weights(enabled, weights);
  // Each pixel's relMSE from both differences where the older one is there: (m_{N/2} - m_{N/4})^2 estimates
  // 2^p (2^p - 1) V(N), so scaled by 2^-p it is a second estimate of what the newest difference estimates.
  const int width = film.width, height = film.height;
  std::vector<double> per_pixel(film.pixel_count(), 0.0);
  const double older_scale = std::exp2(-image.exponent);
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  double at[1 + kNoiseCheckpoints];
  for (size_t i = 0; i < per_pixel.size(); ++i) {
    double sum = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      s->pass_averages(3 * i + c, passes_at);
      s->image_averages(passes_at, image_weights, at);
      const double d = at[1] - at[2];
      double squared = d * d;
      if (s->levels > 2) {
        const double e = at[2] - at[3];
        squared = 0.5 * (squared + e * e * older_scale);
      }
      sum += squared * inverse_denominator(at[0]);
    }
    per_pixel[i] = sum / 3.0 * factor;
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
