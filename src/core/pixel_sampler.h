// The numbers a pixel's estimators draw, as a pure function of (seed, pixel, purpose, sample, dimension), so that
// an image never depends on which thread rendered which tile. Two kinds:
//  - independent: a PCG stream per pixel, frame and purpose, drawn in order (Lueur's first sampler);
//  - sobol: for each dimension a padded pair of Owen-scrambled Sobol dimensions, its index shuffled by a nested
//    uniform scramble, both seeded per pixel, purpose and dimension (Burley 2020). The sample index runs over the
//    frames (frame x samples per frame + the sample), so a pixel's accumulation is one progressive low-discrepancy
//    sequence per dimension, stratified at every power of two.
// Depends on core only.
#pragma once

#include <array>
#include <bit>
#include <string_view>

#include "core/math.h"
#include "core/rng.h"
#include "core/sobol.h"

namespace lueur {

enum class SamplerKind : int { kIndependent = 0, kSobol = 1 };

/// How many samples the estimators draw at once with PixelSampler's batch draws (any count works; this one keeps
/// their arrays on the stack and their loops a whole number of SIMD lanes).
inline constexpr int kSampleBatch = 16;
inline constexpr std::array<std::string_view, 2> kSamplerKindNames = {"independent", "sobol"};

/// The index of the first sample of run `run` (a frame's, or a bounce's) when each run draws `count` samples of one
/// sequence: runs start a power of two apart, so that the samples of any aligned power-of-two block of runs (the
/// first N frames, and each half of them) lie in one aligned block of the Sobol sequence, in the same places. Each
/// block is then a net, and the two halves of N frames are distributed alike, as the noise estimate assumes
/// (film/noise_estimate.h). With a count of 3, runs 3 apart would put frame 1's samples across two blocks.
constexpr uint64_t first_sample_of_run(uint64_t run, int count) {
  return run * std::bit_ceil(static_cast<uint64_t>(count > 0 ? count : 1));
}

class PixelSampler {
 public:
  /// Each kind makes only its own state: samplers are made several times per pixel and frame.
  PixelSampler(SamplerKind kind, uint64_t seed, uint64_t pixel, uint64_t frame, RngPurpose purpose)
      : kind_(kind),
        rng_(kind == SamplerKind::kIndependent ? make_pixel_rng(seed, pixel, frame, purpose) : Pcg32(0, 0)),
        key_(kind == SamplerKind::kSobol
                 ? hash_combine(hash_combine(hash_combine(seed, pixel), static_cast<uint64_t>(purpose)), 0x50b01ull)
                 : 0) {}

  /// Begins sample `index` of this pixel's sequence for this purpose; its dimensions are counted from 0. (The
  /// independent sampler only draws the next numbers of its stream.)
  void start_sample(uint64_t index) {
    reversed_index_ = reverse_bits(static_cast<uint32_t>(index));  // 2^32 samples per pixel, then it repeats
    dimension_ = 0;
  }

  /// The next dimension of the current sample, in [0, 1).
  float get_1d() {
    if (kind_ == SamplerKind::kIndependent) return rng_.next_float();
    const DimensionSeeds& seeds = next_dimension_seeds();
    return fraction_to_float(scrambled_dimension_0(shuffled_index(seeds.index), seeds.x));
  }

  /// The next two dimensions of the current sample, in [0, 1)^2, stratified together.
  Vec2 get_2d() {
    if (kind_ == SamplerKind::kIndependent) return next_two_of_stream();
    return sobol_2d(next_dimension_seeds());
  }

  /// Dimension pair `d` of the current sample, however many the sample has drawn: for a draw that comes after a
  /// varying number of others (the head-light's point after a batch of light samples). Uncached. (The independent
  /// sampler draws the next two numbers of its stream.)
  Vec2 get_2d_of_dimension(uint32_t d) {
    if (kind_ == SamplerKind::kIndependent) return next_two_of_stream();
    return sobol_2d(seeds_of(d));
  }

  /// For `count` samples from `first_sample` on, what each would give for get_1d then get_2d: an L1 sample's light
  /// choice (`one`) and point on the light (`x`, `y`). The Sobol numbers of all the samples are computed together,
  /// in SIMD lanes.
  void draw_1d_2d(uint64_t first_sample, int count, float* one, float* x, float* y) {
    draw_1d_2d_lanes(
        count, [first_sample](int k) { return first_sample + static_cast<uint64_t>(k); }, one, x, y);
  }

  /// draw_1d_2d for `runs` runs of `count` samples each (at most kSampleBatch in all), run r from
  /// `first_samples[r]` on, into consecutive lanes: L1 at several surface points at once.
  void draw_1d_2d_runs(const uint64_t* first_samples, int runs, int count, float* one, float* x, float* y) {
    std::array<uint32_t, kSampleBatch> samples;  // the sequence repeats after 2^32 samples (start_sample)
    int lanes = 0;
    for (int r = 0; r < runs; ++r)
      for (int k = 0; k < count; ++k)
        samples[static_cast<size_t>(lanes++)] = static_cast<uint32_t>(first_samples[r] + static_cast<uint64_t>(k));
    draw_1d_2d_lanes(lanes, [&samples](int k) { return samples[static_cast<size_t>(k)]; }, one, x, y);
  }

  /// For `count` samples from `first_sample` on, what each would give for get_2d: a bounce or AO direction.
  void draw_2d(uint64_t first_sample, int count, float* x, float* y) {
    if (kind_ == SamplerKind::kIndependent) {
      for (int k = 0; k < count; ++k) {
        start_sample(first_sample + static_cast<uint64_t>(k));
        const Vec2 u = get_2d();
        x[k] = u.x;
        y[k] = u.y;
      }
      return;
    }
    const DimensionSeeds seeds = seeds_of(0);
    for (int k = 0; k < count; ++k) {
      const uint32_t index = lane_index(
          reverse_bits_by_shifts(static_cast<uint32_t>(first_sample + static_cast<uint64_t>(k))), seeds.index);
      x[k] = lane_dimension_0(index, seeds.x);
      y[k] = lane_dimension_1(index, seeds.y);
    }
  }

 private:
  /// draw_1d_2d's numbers for `count` lanes, lane k drawing sample `sample_of(k)`.
  template <class SampleOf>
  void draw_1d_2d_lanes(int count, SampleOf sample_of, float* one, float* x, float* y) {
    if (kind_ == SamplerKind::kIndependent) {
      for (int k = 0; k < count; ++k) {
        start_sample(sample_of(k));
        one[k] = get_1d();
        const Vec2 u = get_2d();
        x[k] = u.x;
        y[k] = u.y;
      }
      return;
    }
    const DimensionSeeds first = seeds_of(0), second = seeds_of(1);
    for (int k = 0; k < count; ++k) {
      const uint32_t reversed = reverse_bits_by_shifts(static_cast<uint32_t>(sample_of(k)));
      one[k] = lane_dimension_0(lane_index(reversed, first.index), first.x);
      const uint32_t index = lane_index(reversed, second.index);
      x[k] = lane_dimension_0(index, second.x);
      y[k] = lane_dimension_1(index, second.y);
    }
  }

  /// The scrambling seeds of one dimension (pair): for the index shuffle and for each coordinate.
  struct DimensionSeeds {
    uint32_t index = 0, x = 0, y = 0;
  };

  /// The seeds of dimension `d`: functions of the pixel, purpose and dimension only.
  DimensionSeeds seeds_of(uint32_t d) const {
    const uint64_t h = mix64(key_ ^ (0x9e3779b97f4a7c15ull * (d + 1)));
    return {static_cast<uint32_t>(h), static_cast<uint32_t>(h >> 32), static_cast<uint32_t>(mix64(h))};
  }

  /// The independent sampler's next two numbers, in order.
  Vec2 next_two_of_stream() {
    const float u1 = rng_.next_float();
    return Vec2(u1, rng_.next_float());
  }

  /// The current sample's two coordinates in the dimension pair whose seeds are `seeds`, stratified together.
  Vec2 sobol_2d(const DimensionSeeds& seeds) const {
    const uint32_t index = shuffled_index(seeds.index);
    return Vec2(fraction_to_float(scrambled_dimension_0(index, seeds.x)),
                fraction_to_float(reverse_bits(laine_karras_permutation(sobol_dimension_1_reversed(index), seeds.y))));
  }

  /// The seeds of the next dimension, those of the first few kept for the pixel's next samples.
  const DimensionSeeds& next_dimension_seeds() {
    const uint32_t d = dimension_++;
    if (d < cached_) return cache_[d];
    DimensionSeeds& seeds = d < kCachedDimensions ? cache_[cached_++] : uncached_;
    seeds = seeds_of(d);
    return seeds;
  }

  /// The sample's index, nested-uniform scrambled: nested_uniform_scramble(index, seed), without reversing the
  /// index's bits again.
  uint32_t shuffled_index(uint32_t seed) const { return reverse_bits(laine_karras_permutation(reversed_index_, seed)); }

  /// nested_uniform_scramble(sobol_dimension_0(index), seed): Sobol's first dimension is the index reversed, so the
  /// scramble's own reversal cancels it.
  static uint32_t scrambled_dimension_0(uint32_t index, uint32_t seed) {
    return reverse_bits(laine_karras_permutation(index, seed));
  }

  /// The batch forms of shuffled_index and of the two coordinates (`reversed`: the sample's index, bits reversed):
  /// the same numbers in arithmetic only (no table lookups), so that a loop over samples vectorises.
  static uint32_t lane_index(uint32_t reversed, uint32_t seed) {
    return reverse_bits_by_shifts(laine_karras_permutation(reversed, seed));
  }
  static float lane_dimension_0(uint32_t index, uint32_t seed) {
    return fraction_to_float(reverse_bits_by_shifts(laine_karras_permutation(index, seed)));
  }
  static float lane_dimension_1(uint32_t index, uint32_t seed) {
    return fraction_to_float(reverse_bits_by_shifts(laine_karras_permutation(sobol_dimension_1_reversed(index), seed)));
  }

  SamplerKind kind_;
  Pcg32 rng_;
  uint64_t key_;
  uint32_t reversed_index_ = 0;  ///< the sample's index, bits reversed
  uint32_t dimension_ = 0;
  static constexpr uint32_t kCachedDimensions = 4;  ///< more than any estimator draws per sample, but kAll's
  std::array<DimensionSeeds, kCachedDimensions> cache_{};
  uint32_t cached_ = 0;
  DimensionSeeds uncached_;
};

}  // namespace lueur
