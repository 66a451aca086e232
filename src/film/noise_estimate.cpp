// The noise estimate from the film's power-of-two snapshots (the derivation is in the header).
#include "film/noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace lueur {
namespace {

using PassWeights = std::array<float, kPassCount>;

/// The relMSE's regulariser: errors on black pixels count as errors on a value of 0.1.
constexpr double kDenominatorFloor = 0.01;

/// The rates the decay mixes: independent sampling's 1 / n, and faster ones up to a smooth 2D integrand's 1 / n^3
/// under Owen scrambling.
constexpr std::array<double, 3> kRates = {1.0, 2.0, 3.0};

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
  /// Adds one pixel channel's squared differences, each times `inverse` (one over its denominator).
  void add(const double* at, int levels, double inverse) {
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
  void add(const double* at, int levels) { add(at, levels, inverse_denominator(at[0])); }
};

/// What the weighted image's estimate reads: its own differences, and each pass's in the image's units (the pass's
/// weight squared over the image's denominator), whose sum is the image's but for the passes' correlation.
struct ImageDifferences {
  Differences image;
  std::array<Differences, kPassCount> passes;
  void add(const Snapshots& s, const double (&passes_at)[kPassCount][1 + kNoiseCheckpoints],
           const PassWeights& weights) {
    double at[1 + kNoiseCheckpoints];
    s.image_averages(passes_at, weights, at);
    const double inverse = inverse_denominator(at[0]);
    image.add(at, s.levels, inverse);
    for (size_t p = 0; p < kPassCount; ++p) {
      if (weights[p] == 0.0f || !s.sums[p][0]) continue;
      const double w = static_cast<double>(weights[p]);
      passes[p].add(passes_at[p], s.levels, w * w * inverse);
    }
  }
};

/// The relMSE-scaled squared half-differences D(N), D(N/2), D(N/4) of a weighted image.
std::array<double, 3> scaled_differences(const Differences& sums, const Film& film) {
  const double values = 3.0 * static_cast<double>(film.pixel_count());
  return {sums.newest / values, sums.older / values, sums.oldest / values};
}

NoiseEstimate estimate_from(const Differences& sums, const Film& film, SamplerKind sampler) {
  const uint64_t newest = film.checkpoints[0].frames;
  std::array<double, 3> d = scaled_differences(sums, film);
  NoiseEstimate e;
  e.known = true;
  if (sampler == SamplerKind::kIndependent) {
    // V(n) = V(1) / n: D(N) estimates V(N), D(N/2) = V(N/2) = 2 V(N) and D(N/4) = 4 V(N), each uncorrelated with the
    // others, so the mean of the three, so scaled, is the same estimate with about a third of its variance.
    double variance = d[0];
    int levels = 1;
    if (film.checkpoints[2].frames > 0) {
      variance += 0.5 * d[1];
      ++levels;
    }
    if (film.checkpoints[3].frames > 0) {
      variance += 0.25 * d[2];
      ++levels;
    }
    e.decay.frames = static_cast<double>(newest);
    e.decay.weights = {variance / levels, 0.0, 0.0};
  } else {
    const int levels = 1 + (film.checkpoints[2].frames > 0 ? 1 : 0) + (film.checkpoints[3].frames > 0 ? 1 : 0);
    e.decay = fit_variance_decay(newest, d.data(), levels);
  }
  const double now = static_cast<double>(film.frames);
  e.rel_mse = e.decay.at(now);
  e.exponent = e.decay.exponent_at(now);
  return e;
}

PassWeights enabled_weights(const std::array<bool, kPassCount>& enabled, const PassWeights& weights) {
  PassWeights w{};
  for (size_t p = 0; p < kPassCount; ++p) w[p] = enabled[p] ? weights[p] : 0.0f;
  return w;
}

/// The weighted image's differences, summed over its pixel channels.
ImageDifferences image_differences(const Film& film, const Snapshots& s, const PassWeights& image_weights) {
  ImageDifferences sums;
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  for (size_t j = 0; j < 3 * film.pixel_count(); ++j) {
    s.pass_averages(j, passes_at);
    sums.add(s, passes_at, image_weights);
  }
  return sums;
}

/// The weighted image's estimate. Independent frames: from its own differences. Sobol frames: each pass's decay is
/// fitted on its differences in the image's units, the decays are summed, and the sum is scaled to give the image's
/// own newest difference (which holds the passes' correlation). The passes fall at different rates (Le steeply at
/// first, L1 and L2 slowly), and one fit of their sum, steered by the steep one in the older differences,
/// understated the image's error after 16 frames of the default settings by a third.
NoiseEstimate image_estimate_from(const ImageDifferences& sums, const Film& film, SamplerKind sampler) {
  if (sampler == SamplerKind::kIndependent) return estimate_from(sums.image, film, sampler);
  VarianceDecay total;
  total.frames = static_cast<double>(film.checkpoints[0].frames);
  for (const Differences& pass : sums.passes) {
    if (!(pass.newest > 0.0)) continue;
    const VarianceDecay decay = estimate_from(pass, film, sampler).decay;
    for (size_t k = 0; k < total.weights.size(); ++k) total.weights[k] += decay.weights[k];
  }
  const double fitted_newest = total.at(0.5 * total.frames) - total.at(total.frames);
  const double observed_newest = scaled_differences(sums.image, film)[0];
  if (!(fitted_newest > 0.0)) return estimate_from(sums.image, film, sampler);
  for (double& w : total.weights) w *= observed_newest / fitted_newest;
  NoiseEstimate e;
  e.known = true;
  e.decay = total;
  e.rel_mse = total.at(static_cast<double>(film.frames));
  e.exponent = total.exponent_at(static_cast<double>(film.frames));
  return e;
}

/// The least-squares problem of fitting the decay's weights: with n measured in units of the newest frame count,
/// level i sits at n = 2^-i, where the rate n^-k gives the difference (2^k - 1) 2^(i k). Each row is divided by its
/// observed difference (relative residuals) and weighed by 2^-i, so that the newest difference counts most.
struct DecayRows {
  double rows[3][3] = {}, targets[3] = {};
  int count = 0;
  double residual(const std::array<double, 3>& weights) const {
    double sum = 0.0;
    for (int r = 0; r < count; ++r) {
      double fitted = 0.0;
      for (size_t k = 0; k < 3; ++k) fitted += rows[r][k] * weights[k];
      sum += (fitted - targets[r]) * (fitted - targets[r]);
    }
    return sum;
  }
};

DecayRows decay_rows(const double* differences, int levels) {
  DecayRows rows;
  for (int i = 0; i < levels; ++i) {
    if (!(differences[i] > 0.0)) continue;  // an unseen level says nothing
    const double weight = std::exp2(-i);
    for (size_t k = 0; k < kRates.size(); ++k)
      rows.rows[rows.count][k] = (std::exp2(kRates[k]) - 1.0) * std::exp2(i * kRates[k]) * weight / differences[i];
    rows.targets[rows.count] = weight;
    ++rows.count;
  }
  return rows;
}

/// The least-squares weights of the rates in `subset` (bit k: rate k + 1), the others 0; none unless there are at
/// least as many rows as rates and every weight comes out positive. Normal equations, solved by Gauss-Jordan
/// elimination with partial pivoting.
std::optional<std::array<double, 3>> positive_least_squares(const DecayRows& rows, unsigned subset) {
  int columns[3], size = 0;
  for (int k = 0; k < 3; ++k)
    if (subset & (1u << k)) columns[size++] = k;
  if (size > rows.count) return std::nullopt;
  double a[3][4] = {};
  for (int r = 0; r < size; ++r) {
    for (int row = 0; row < rows.count; ++row) {
      for (int c = 0; c < size; ++c) a[r][c] += rows.rows[row][columns[r]] * rows.rows[row][columns[c]];
      a[r][size] += rows.rows[row][columns[r]] * rows.targets[row];
    }
  }
  for (int c = 0; c < size; ++c) {
    int pivot = c;
    for (int r = c + 1; r < size; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
    if (!(std::fabs(a[pivot][c]) > 1e-300)) return std::nullopt;
    std::swap(a[c], a[pivot]);
    for (int r = 0; r < size; ++r) {
      if (r == c) continue;
      const double f = a[r][c] / a[c][c];
      for (int k = c; k <= size; ++k) a[r][k] -= f * a[c][k];
    }
  }
  std::array<double, 3> weights{};
  for (int c = 0; c < size; ++c) {
    const double w = a[c][size] / a[c][c];
    if (!(w > 0.0)) return std::nullopt;
    weights[static_cast<size_t>(columns[c])] = w;
  }
  return weights;
}

}  // namespace

double VarianceDecay::at(double n) const {
  const double x = frames / n;
  return weights[0] * x + weights[1] * x * x + weights[2] * x * x * x;
}

double VarianceDecay::exponent_at(double n) const {
  const double x = frames / n;
  const double terms[3] = {weights[0] * x, weights[1] * x * x, weights[2] * x * x * x};
  const double sum = terms[0] + terms[1] + terms[2];
  return sum > 0.0 ? (terms[0] + 2.0 * terms[1] + 3.0 * terms[2]) / sum : 1.0;
}

VarianceDecay fit_variance_decay(uint64_t newest_frames, const double* differences, int count) {
  VarianceDecay decay;
  decay.frames = static_cast<double>(newest_frames);
  if (count < 1 || !(differences[0] > 0.0)) return decay;  // no noise seen: none estimated
  const DecayRows rows = decay_rows(differences, std::min(count, 3));
  // Every subset of the rates, smallest first, so that among equally good fits the slowest (most cautious) wins;
  // a subset whose least-squares weights are not all positive is no candidate.
  double best_residual = std::numeric_limits<double>::infinity();
  for (const unsigned subset : {1u, 2u, 4u, 3u, 5u, 6u, 7u}) {  // bit k: rate k + 1
    const std::optional<std::array<double, 3>> weights = positive_least_squares(rows, subset);
    if (!weights) continue;
    const double residual = rows.residual(*weights);
    // A relative margin, so that an exact fit by more rates does not beat an exact fit by fewer on rounding.
    if (residual < best_residual * (1.0 - 1e-9) - 1e-24) {
      best_residual = residual;
      decay.weights = *weights;
    }
  }
  return decay;
}

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
  ImageDifferences image;
  const size_t values = 3 * film.pixel_count();
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  for (size_t j = 0; j < values; ++j) {
    s->pass_averages(j, passes_at);
    for (size_t p = 0; p < kPassCount; ++p)
      if (!film.sums[p].empty()) passes[p].add(passes_at[p], s->levels);
    image.add(*s, passes_at, image_weights);
  }
  for (size_t p = 0; p < kPassCount; ++p)
    if (!film.sums[p].empty()) noise.passes[p] = estimate_from(passes[p], film, sampler);
  noise.image = image_estimate_from(image, film, sampler);
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
  return image_estimate_from(image_differences(film, *s, enabled_weights(enabled, weights)), film, sampler);
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
    if (!e.known || film.frames <= made_at_) return;
    e.rel_mse = e.decay.at(static_cast<double>(film.frames));
    e.exponent = e.decay.exponent_at(static_cast<double>(film.frames));
  };
  for (NoiseEstimate& e : noise_.passes) carry(e);
  carry(noise_.image);
  return noise_;
}

Image pixel_noise_map(const Film& film, const std::array<bool, kPassCount>& enabled,
                      const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  const std::optional<Snapshots> s = snapshots_of(film, sampler);
  if (!s) return {};
  const PassWeights image_weights = enabled_weights(enabled, weights);
  const ImageDifferences image_sums = image_differences(film, *s, image_weights);
  const NoiseEstimate image = image_estimate_from(image_sums, film, sampler);
  const std::array<double, 3> d = scaled_differences(image_sums.image, film);
  // A pixel's squared newest difference times what turns the image's into its relMSE now. Where the older difference
  // is there, it is a second estimate of the same, scaled by the image's ratio of the two.
  const double factor = d[0] > 0.0 ? image.rel_mse / d[0] : 0.0;
  const double older_scale = s->levels > 2 && d[1] > 0.0 ? d[0] / d[1] : 0.0;
  const int width = film.width, height = film.height;
  std::vector<double> per_pixel(film.pixel_count(), 0.0);
  double passes_at[kPassCount][1 + kNoiseCheckpoints];
  double at[1 + kNoiseCheckpoints];
  for (size_t i = 0; i < per_pixel.size(); ++i) {
    double sum = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      s->pass_averages(3 * i + c, passes_at);
      s->image_averages(passes_at, image_weights, at);
      const double e = at[1] - at[2];
      double squared = e * e;
      if (older_scale > 0.0) {
        const double older = at[2] - at[3];
        squared = 0.5 * (squared + older * older * older_scale);
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
