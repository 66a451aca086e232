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
#include <string_view>

#include "core/math.h"
#include "core/rng.h"
#include "core/sobol.h"

namespace lueur {

enum class SamplerKind : int { kIndependent = 0, kSobol = 1 };
inline constexpr std::array<std::string_view, 2> kSamplerKindNames = {"independent", "sobol"};

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
    if (kind_ == SamplerKind::kIndependent) {
      const float u1 = rng_.next_float();
      return Vec2(u1, rng_.next_float());
    }
    const DimensionSeeds& seeds = next_dimension_seeds();
    const uint32_t index = shuffled_index(seeds.index);
    const uint32_t y_reversed = xor_by_bytes(kReversedDimension1Tables, index);  // reverse_bits(sobol_dimension_1)
    return Vec2(fraction_to_float(scrambled_dimension_0(index, seeds.x)),
                fraction_to_float(reverse_bits(laine_karras_permutation(y_reversed, seeds.y))));
  }

 private:
  /// Sobol's second dimension with its bits reversed, as tables: the scramble works on reversed bits.
  static constexpr SobolByteTables kReversedDimension1Tables = [] {
    std::array<uint32_t, 32> reversed{};
    for (size_t j = 0; j < reversed.size(); ++j) reversed[j] = reverse_bits(kSobolDimension1Directions[j]);
    return make_sobol_byte_tables(reversed);
  }();

  /// The scrambling seeds of one dimension (pair): for the index shuffle and for each coordinate.
  struct DimensionSeeds {
    uint32_t index = 0, x = 0, y = 0;
  };

  /// The seeds of the next dimension. They depend on the pixel, purpose and dimension only, not on the sample, so
  /// those of the first few dimensions are kept for the pixel's next samples.
  const DimensionSeeds& next_dimension_seeds() {
    const uint32_t d = dimension_++;
    if (d < cached_) return cache_[d];
    const uint64_t h = mix64(key_ ^ (0x9e3779b97f4a7c15ull * (d + 1)));
    DimensionSeeds& seeds = d < kCachedDimensions ? cache_[cached_++] : uncached_;
    seeds = {static_cast<uint32_t>(h), static_cast<uint32_t>(h >> 32), static_cast<uint32_t>(mix64(h))};
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
