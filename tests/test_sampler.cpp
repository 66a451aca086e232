// The pixel samplers: Sobol's first two dimensions are a (0,2)-sequence, and so is every dimension pair the sobol
// sampler draws (Owen scrambling and index shuffling keep it), at every power of two and in every aligned block;
// its estimates are unbiased over seeds, and their error falls faster than 1/N on a smooth integrand, where the
// independent sampler's falls as 1/N. The independent sampler is the PCG stream Lueur always drew.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/pixel_sampler.h"

namespace lueur {
namespace {

/// Whether `points` (2^k of them in [0,1)^2) put exactly one point in every elementary interval
/// [a / 2^m, (a + 1) / 2^m) x [b / 2^(k-m), (b + 1) / 2^(k-m)), for every m from 0 to k.
bool is_02_net(const std::vector<Vec2>& points, int k, std::string& why) {
  const size_t n = size_t{1} << k;
  if (points.size() != n) {
    why = "not 2^k points";
    return false;
  }
  for (int m = 0; m <= k; ++m) {
    const size_t cols = size_t{1} << m, rows = size_t{1} << (k - m);
    std::vector<int> count(n, 0);
    for (const Vec2& p : points) {
      const size_t a = static_cast<size_t>(p.x * static_cast<float>(cols)),
                   b = static_cast<size_t>(p.y * static_cast<float>(rows));
      if (a >= cols || b >= rows) {
        why = "a point outside [0,1)^2";
        return false;
      }
      if (++count[a * rows + b] > 1) {
        why = "two points in the interval " + std::to_string(a) + "/" + std::to_string(cols) + " x " +
              std::to_string(b) + "/" + std::to_string(rows);
        return false;
      }
    }
  }
  return true;
}

/// Points `first` to `first + 2^k - 1` of the sampler's dimension pair number `pair` (after `pair` earlier draws of
/// two dimensions each), for one pixel.
std::vector<Vec2> sampler_points(SamplerKind kind, uint64_t seed, uint64_t pixel, int pair, uint64_t first, int k) {
  PixelSampler sampler(kind, seed, pixel, 0, RngPurpose::kDirect);
  std::vector<Vec2> points;
  for (uint64_t i = first; i < first + (uint64_t{1} << k); ++i) {
    sampler.start_sample(i);
    for (int d = 0; d < pair; ++d) sampler.get_2d();
    points.push_back(sampler.get_2d());
  }
  return points;
}

// The run-time bit reversal (byte tables) against the compile-time one (shifts and masks), bit by bit.
TEST(Sobol, BitReversalMovesBitIToBit31MinusI) {
  static_assert(reverse_bits(1u) == 0x80000000u && reverse_bits(0x00000f01u) == 0x80f00000u);
  for (uint32_t bit = 0; bit < 32; ++bit) ASSERT_EQ(reverse_bits(1u << bit), 1u << (31 - bit)) << bit;
  uint32_t x = 12345u;
  for (int i = 0; i < 100000; ++i) {
    x = x * 1664525u + 1013904223u;
    uint32_t expected = 0;
    for (uint32_t bit = 0; bit < 32; ++bit) expected |= ((x >> bit) & 1u) << (31 - bit);
    ASSERT_EQ(reverse_bits(x), expected) << x;
  }
}

// The table-free second dimension against its definition: the xor of the direction numbers of the index's set bits.
TEST(Sobol, SecondDimensionIsTheXorOfItsDirectionNumbers) {
  uint32_t index = 1u;
  for (int i = 0; i < 100000; ++i) {
    index = index * 1664525u + 1013904223u;
    uint32_t expected = 0;
    for (uint32_t bit = 0; bit < 32; ++bit)
      if (index & (1u << bit)) expected ^= kSobolDimension1Directions[bit];
    ASSERT_EQ(sobol_dimension_1(index), expected) << index;
    ASSERT_EQ(sobol_dimension_1_reversed(index), reverse_bits(expected)) << index;
  }
  for (uint32_t bit = 0; bit < 32; ++bit) ASSERT_EQ(sobol_dimension_1(1u << bit), kSobolDimension1Directions[bit]);
}

// The batch draws give, sample for sample, what start_sample + get_1d / get_2d give, for both kinds and for ranges
// that start anywhere (the L1 batches start at frame x rays).
TEST(PixelSampler, BatchDrawsEqualTheSampleBySampleDraws) {
  for (const SamplerKind kind : {SamplerKind::kSobol, SamplerKind::kIndependent}) {
    for (const uint64_t first : {uint64_t{0}, uint64_t{16}, uint64_t{37}, uint64_t{4096 * 16 + 5}}) {
      constexpr int kCount = 13;
      float one[kCount], x[kCount], y[kCount];
      PixelSampler batch(kind, 9, 1234, first, RngPurpose::kDirect), single(kind, 9, 1234, first, RngPurpose::kDirect);
      batch.draw_1d_2d(first, kCount, one, x, y);
      for (int k = 0; k < kCount; ++k) {
        single.start_sample(first + static_cast<uint64_t>(k));
        ASSERT_EQ(one[k], single.get_1d()) << k;
        const Vec2 u = single.get_2d();
        ASSERT_EQ(x[k], u.x) << k;
        ASSERT_EQ(y[k], u.y) << k;
      }
      PixelSampler batch2(kind, 9, 77, first, RngPurpose::kIndirect),
          single2(kind, 9, 77, first, RngPurpose::kIndirect);
      batch2.draw_2d(first, kCount, x, y);
      for (int k = 0; k < kCount; ++k) {
        single2.start_sample(first + static_cast<uint64_t>(k));
        const Vec2 u = single2.get_2d();
        ASSERT_EQ(x[k], u.x) << k;
        ASSERT_EQ(y[k], u.y) << k;
      }
    }
  }
}

TEST(Sobol, FirstTwoDimensionsAreA02Sequence) {
  for (int k = 0; k <= 12; ++k)
    for (uint32_t block = 0; block < 3; ++block) {
      std::vector<Vec2> points;
      const uint32_t n = 1u << k;
      for (uint32_t i = block * n; i < (block + 1) * n; ++i)
        points.emplace_back(fraction_to_float(sobol_dimension_0(i)), fraction_to_float(sobol_dimension_1(i)));
      std::string why;
      EXPECT_TRUE(is_02_net(points, k, why)) << "2^" << k << " points, block " << block << ": " << why;
    }
}

TEST(Sobol, NestedUniformScrambleIsABijectionThatKeepsTheCoarseBitsNested) {
  // Each bit depends only on the bits above it: two fractions that share their top b bits still do after the
  // scramble, and the scramble of all 2^16 16-bit prefixes is a permutation of them.
  for (const uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
    std::vector<bool> seen(1u << 16, false);
    for (uint32_t top = 0; top < (1u << 16); ++top) {
      const uint32_t a = nested_uniform_scramble(top << 16, seed),
                     b = nested_uniform_scramble((top << 16) | 0x1234u, seed);
      ASSERT_EQ(a >> 16, b >> 16) << "bits leaked upward";
      ASSERT_FALSE(seen[a >> 16]) << "two prefixes scrambled to one";
      seen[a >> 16] = true;
    }
  }
}

TEST(SobolSampler, EveryDimensionPairIsA02NetAtEveryPowerOfTwo) {
  for (const uint64_t pixel : {0ull, 1ull, 77777ull})
    for (const int pair : {0, 1, 5})
      for (int k = 0; k <= 10; ++k)
        for (const uint64_t block : {0ull, 1ull, 6ull}) {
          std::string why;
          EXPECT_TRUE(is_02_net(sampler_points(SamplerKind::kSobol, 42, pixel, pair, block << k, k), k, why))
              << "pixel " << pixel << ", pair " << pair << ", samples " << (block << k) << " + 2^" << k << ": " << why;
        }
  // The independent sampler is not stratified: 1024 of its points fall twice in some interval.
  std::string why;
  EXPECT_FALSE(is_02_net(sampler_points(SamplerKind::kIndependent, 42, 0, 0, 0, 10), 10, why));
}

TEST(SobolSampler, OneDimensionIsStratifiedAtEveryPowerOfTwo) {
  for (int k = 0; k <= 12; ++k) {
    PixelSampler sampler(SamplerKind::kSobol, 9, 123, 0, RngPurpose::kIndirect);
    const size_t n = size_t{1} << k;
    std::vector<int> count(n, 0);
    for (size_t i = 0; i < n; ++i) {
      sampler.start_sample(i);
      sampler.get_2d();  // a dimension pair before it
      ++count[static_cast<size_t>(sampler.get_1d() * static_cast<float>(n))];
    }
    for (size_t j = 0; j < n; ++j) ASSERT_EQ(count[j], 1) << "2^" << k << " samples, interval " << j;
  }
}

TEST(SobolSampler, PixelsPurposesAndDimensionsAreDecorrelated) {
  const auto first = [](uint64_t seed, uint64_t pixel, RngPurpose purpose, int pair) {
    PixelSampler sampler(SamplerKind::kSobol, seed, pixel, 0, purpose);
    sampler.start_sample(0);
    for (int d = 0; d < pair; ++d) sampler.get_2d();
    return sampler.get_2d();
  };
  const Vec2 base = first(1, 5, RngPurpose::kDirect, 0);
  EXPECT_EQ(first(1, 5, RngPurpose::kDirect, 0), base) << "a pure function of its inputs";
  EXPECT_NE(first(2, 5, RngPurpose::kDirect, 0), base);
  EXPECT_NE(first(1, 6, RngPurpose::kDirect, 0), base);
  EXPECT_NE(first(1, 5, RngPurpose::kIndirect, 0), base);
  EXPECT_NE(first(1, 5, RngPurpose::kDirect, 1), base);
  // The frame does not choose the point: the sample index does, so the frames make one sequence.
  PixelSampler other_frame(SamplerKind::kSobol, 1, 5, 9, RngPurpose::kDirect);
  other_frame.start_sample(0);
  EXPECT_EQ(other_frame.get_2d(), base);
}

TEST(IndependentSampler, DrawsThePixelStreamInOrder) {
  PixelSampler sampler(SamplerKind::kIndependent, 7, 1234, 5, RngPurpose::kDirect);
  Pcg32 stream = make_pixel_rng(7, 1234, 5, RngPurpose::kDirect);
  for (int i = 0; i < 100; ++i) {
    sampler.start_sample(static_cast<uint64_t>(i) * 977);  // ignored: the stream goes on
    EXPECT_EQ(sampler.get_1d(), stream.next_float());
    const Vec2 u = sampler.get_2d();
    EXPECT_EQ(u.x, stream.next_float());
    EXPECT_EQ(u.y, stream.next_float());
  }
}

/// A smooth integrand over the unit square and its integral: (e - 1) (2 / pi).
double smooth(Vec2 u) { return std::exp(static_cast<double>(u.x)) * std::sin(3.14159265358979 * u.y); }
const double kSmoothIntegral = (std::exp(1.0) - 1.0) * 2.0 / 3.14159265358979;

/// The N-sample estimate of the smooth integral, from a sampler seeded with `seed`, one dimension pair in.
double estimate(SamplerKind kind, uint64_t seed, int n) {
  PixelSampler sampler(kind, seed, 3, 0, RngPurpose::kIndirect);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    sampler.start_sample(static_cast<uint64_t>(i));
    sampler.get_2d();
    sum += smooth(sampler.get_2d());
  }
  return sum / n;
}

struct ErrorStats {
  double mean = 0.0, standard_error = 0.0, mse = 0.0;
};

ErrorStats over_seeds(SamplerKind kind, int n, int seeds) {
  double sum = 0.0, sum2 = 0.0, squared_error = 0.0;
  for (int s = 0; s < seeds; ++s) {
    const double x = estimate(kind, static_cast<uint64_t>(s) + 1000, n);
    sum += x;
    sum2 += x * x;
    squared_error += (x - kSmoothIntegral) * (x - kSmoothIntegral);
  }
  const double mean = sum / seeds;
  return {mean, std::sqrt(std::max(0.0, sum2 / seeds - mean * mean) / (seeds - 1)), squared_error / seeds};
}

TEST(SobolSampler, IsUnbiasedOverSeeds) {
  for (const int n : {1, 3, 16, 100}) {
    const ErrorStats stats = over_seeds(SamplerKind::kSobol, n, 4000);
    EXPECT_NEAR(stats.mean, kSmoothIntegral, 5.0 * stats.standard_error + 1e-7) << n << " samples";
  }
}

TEST(SobolSampler, ErrorFallsFasterThanOneOverN) {
  // Owen-scrambled nets on a smooth integrand: variance about N^-3; independent samples: N^-1. From 16 to 256
  // samples the first falls by thousands, the second by 16.
  const double sobol = over_seeds(SamplerKind::kSobol, 16, 500).mse / over_seeds(SamplerKind::kSobol, 256, 500).mse;
  const double independent =
      over_seeds(SamplerKind::kIndependent, 16, 500).mse / over_seeds(SamplerKind::kIndependent, 256, 500).mse;
  EXPECT_GT(sobol, 256.0) << "mean squared error 16 -> 256 samples fell by " << sobol;
  EXPECT_GT(independent, 8.0);
  EXPECT_LT(independent, 32.0) << "independent samples: about 16x";
}

}  // namespace
}  // namespace lueur
