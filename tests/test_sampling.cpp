// Sampling warps and light selection against their probability mass/density functions (chi-square), and the
// report's Algorithm 1 against the cumulative table.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/spherical_triangle.h"
#include "lights/light_sampler.h"
#include "scene/default_scene.h"
#include "test_support.h"

namespace lueur {
namespace {

TEST(Rng, StreamsArePureFunctionsOfTheirKey) {
  Pcg32 a = make_pixel_rng(7, 1234, 5, RngPurpose::kDirect);
  Pcg32 b = make_pixel_rng(7, 1234, 5, RngPurpose::kDirect);
  Pcg32 other_frame = make_pixel_rng(7, 1234, 6, RngPurpose::kDirect);
  int same_as_other = 0;
  for (int i = 0; i < 100; ++i) {
    const uint32_t x = a.next_u32();
    EXPECT_EQ(x, b.next_u32());
    same_as_other += x == other_frame.next_u32();
  }
  EXPECT_LT(same_as_other, 3);
}

TEST(Rng, FloatsAreUniformInUnitInterval) {
  Pcg32 rng(42, 3);
  constexpr int kBins = 64, kSamples = 640000;
  std::vector<int> counts(kBins, 0);
  for (int i = 0; i < kSamples; ++i) {
    const float u = rng.next_float();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++counts[static_cast<size_t>(u * kBins)];
  }
  double chi2 = 0.0;
  const double expected = static_cast<double>(kSamples) / kBins;
  for (const int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_FALSE(test::chi_square_rejects(chi2, kBins - 1)) << chi2;
}

// Uniform points on the triangle (0,0) (1,0) (0,1), binned on an N x N grid: cells below the diagonal have area
// 1/N^2, cells cut by it 1/(2 N^2); the density is 2 (one over the triangle's area).
TEST(Sampling, UniformTriangleMatchesItsPdf) {
  constexpr int kGrid = 16, kSamples = 400000;
  std::vector<int> counts(kGrid * kGrid, 0);
  Pcg32 rng(1, 1);
  for (int i = 0; i < kSamples; ++i) {
    const Vec2 b = sample_uniform_triangle(rng.next_float(), rng.next_float());
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    const int cx = std::min(static_cast<int>(b.x * kGrid), kGrid - 1);
    const int cy = std::min(static_cast<int>(b.y * kGrid), kGrid - 1);
    ++counts[static_cast<size_t>(cy * kGrid + cx)];
  }
  double chi2 = 0.0;
  int cells = 0;
  for (int cy = 0; cy < kGrid; ++cy)
    for (int cx = 0; cx < kGrid; ++cx) {
      const int count = counts[static_cast<size_t>(cy * kGrid + cx)];
      double area = 0.0;
      if (cx + cy < kGrid - 1)
        area = 1.0 / (kGrid * kGrid);
      else if (cx + cy == kGrid - 1)
        area = 0.5 / (kGrid * kGrid);
      if (area == 0.0) {
        EXPECT_EQ(count, 0) << "sample outside the triangle in cell " << cx << "," << cy;
        continue;
      }
      const double expected = kSamples * area * 2.0;
      chi2 += (count - expected) * (count - expected) / expected;
      ++cells;
    }
  EXPECT_FALSE(test::chi_square_rejects(chi2, cells - 1)) << chi2;
}

TEST(Sampling, SphericalTriangleSolidAngles) {
  // An octant's triangle seen from the origin: an eighth of the sphere.
  EXPECT_NEAR(make_spherical_triangle(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)).solid_angle, 0.5 * kPi,
              1e-6);
  // A small triangle far away: its area times cos / d^2.
  const SphericalTriangle far =
      make_spherical_triangle(Vec3(0.0f), Vec3(0, 0, 100), Vec3(0.1f, 0, 100), Vec3(0, 0.1f, 100));
  EXPECT_NEAR(far.solid_angle / (0.005 / 1e4), 1.0, 1e-3);
  // Seen edge-on, or from a corner: nothing to sample.
  EXPECT_EQ(make_spherical_triangle(Vec3(5, 0, 0), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)).solid_angle, 0.0);
  EXPECT_EQ(make_spherical_triangle(Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)).solid_angle, 0.0);
}

/// Samples `count` directions over the triangle as seen from `from` and checks, by chi-square, that they fall on the
/// 32 triangles of a 4 x 4 barycentric grid of it in proportion to those triangles' solid angles; every direction
/// must hit the triangle.
void expect_uniform_in_solid_angle(const Vec3& from, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  constexpr int kGrid = 4, kSamples = 200000;
  const SphericalTriangle whole = make_spherical_triangle(from, p0, p1, p2);
  ASSERT_GT(whole.solid_angle, 0.0);
  const auto corner = [&](int i, int j) {
    return p0 + (static_cast<float>(i) / kGrid) * (p1 - p0) + (static_cast<float>(j) / kGrid) * (p2 - p0);
  };
  std::vector<int> counts(2 * kGrid * kGrid, 0);
  const glm::dvec3 e1 = glm::dvec3(p1 - p0), e2 = glm::dvec3(p2 - p0), origin(from);
  Pcg32 rng(3, 5);
  for (int n = 0; n < kSamples; ++n) {
    const glm::dvec3 d = sample_spherical_triangle(whole, rng.next_float(), rng.next_float());
    ASSERT_NEAR(glm::length(d), 1.0, 1e-9);
    // Where the direction meets the triangle's plane, in barycentrics (Cramer's rule).
    const glm::dvec3 pvec = glm::cross(d, e2);
    const double det = glm::dot(e1, pvec);
    const glm::dvec3 tvec = origin - glm::dvec3(p0);
    const double b1 = glm::dot(tvec, pvec) / det;
    const glm::dvec3 qvec = glm::cross(tvec, e1);
    const double b2 = glm::dot(d, qvec) / det, t = glm::dot(e2, qvec) / det;
    ASSERT_GT(t, 0.0);
    ASSERT_GE(b1, -1e-6);
    ASSERT_GE(b2, -1e-6);
    ASSERT_LE(b1 + b2, 1.0 + 1e-6);
    const double gx = std::clamp(b1 * kGrid, 0.0, kGrid - 1e-9), gy = std::clamp(b2 * kGrid, 0.0, kGrid - 1e-9);
    const int cx = static_cast<int>(gx), cy = static_cast<int>(gy);
    const bool upper = (gx - cx) + (gy - cy) >= 1.0;
    ++counts[static_cast<size_t>(2 * (cy * kGrid + cx) + (upper ? 1 : 0))];
  }
  double chi2 = 0.0;
  int cells = 0;
  for (int cy = 0; cy < kGrid; ++cy)
    for (int cx = 0; cx < kGrid; ++cx)
      for (int upper = 0; upper < 2; ++upper) {
        const int count = counts[static_cast<size_t>(2 * (cy * kGrid + cx) + upper)];
        if (cx + cy + upper >= kGrid) {  // outside the triangle
          EXPECT_LE(count, 2) << cx << "," << cy << "," << upper;
          continue;
        }
        const SphericalTriangle part =
            upper ? make_spherical_triangle(from, corner(cx + 1, cy), corner(cx + 1, cy + 1), corner(cx, cy + 1))
                  : make_spherical_triangle(from, corner(cx, cy), corner(cx + 1, cy), corner(cx, cy + 1));
        const double expected = kSamples * part.solid_angle / whole.solid_angle;
        chi2 += (count - expected) * (count - expected) / expected;
        ++cells;
      }
  EXPECT_FALSE(test::chi_square_rejects(chi2, cells - 1)) << chi2;
}

TEST(Sampling, SphericalTriangleDirectionsAreUniformInSolidAngle) {
  // Seen from afar, from nearby, and from just off the triangle's plane next to one of its edges, where area
  // sampling's weight grows without bound: what the warp is for.
  expect_uniform_in_solid_angle(Vec3(0.2f, 0.3f, 5.0f), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  expect_uniform_in_solid_angle(Vec3(0.2f, 0.1f, 0.3f), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  expect_uniform_in_solid_angle(Vec3(0.4f, -0.02f, 0.01f), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
}

// The numbers warped toward the cosine come as often as the bilinear density they return says: counts in an 8 x 8
// grid against the density's integral over each cell (a bilinear function's mean over a rectangle is its value at
// the centre), and the returned density against the bilinear through the corner cosines.
TEST(Sampling, CosineWarpedNumbersFollowTheirBilinearDensity) {
  const SphericalTriangle t =
      make_spherical_triangle(Vec3(0.1f, 0.2f, 0.0f), Vec3(-2, -1, 1), Vec3(3, 0, 0.5f), Vec3(0, 3, 2));
  ASSERT_GT(t.solid_angle, 0.0);
  const glm::dvec3 normal = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));
  const double at_b = std::max(0.01, glm::dot(normal, t.b)), at_a = std::max(0.01, glm::dot(normal, t.a)),
               at_c = std::max(0.01, glm::dot(normal, t.c));
  const double mean = (2.0 * at_b + at_a + at_c) / 4.0;
  const auto bilinear = [&](double x, double y) {
    return ((1 - x) * (1 - y) * at_b + x * (1 - y) * at_b + (1 - x) * y * at_a + x * y * at_c) / mean;
  };
  constexpr int kGrid = 8, kSamples = 400000;
  std::vector<int> counts(kGrid * kGrid, 0);
  Pcg32 rng(8, 1);
  for (int n = 0; n < kSamples; ++n) {
    double u1 = rng.next_float(), u2 = rng.next_float();
    const double density = warp_toward_cosine(t, normal, u1, u2);
    ASSERT_GE(u1, 0.0);
    ASSERT_LT(u1, 1.0);
    ASSERT_GE(u2, 0.0);
    ASSERT_LT(u2, 1.0);
    ASSERT_NEAR(density, bilinear(u1, u2), 1e-9);
    ++counts[static_cast<size_t>(static_cast<int>(u2 * kGrid) * kGrid + static_cast<int>(u1 * kGrid))];
  }
  double chi2 = 0.0;
  for (int y = 0; y < kGrid; ++y)
    for (int x = 0; x < kGrid; ++x) {
      const double expected = kSamples * bilinear((x + 0.5) / kGrid, (y + 0.5) / kGrid) / (kGrid * kGrid);
      const double count = counts[static_cast<size_t>(y * kGrid + x)];
      chi2 += (count - expected) * (count - expected) / expected;
    }
  EXPECT_FALSE(test::chi_square_rejects(chi2, kGrid * kGrid - 1)) << chi2;
}

// What the warp is for: the projected solid angle of a wide triangle rising from the horizon (a wall of a sky seen
// from the ground: the cosine grows from near 0 at its foot to 0.95 at its top), by Lambert's formula, estimated from
// directions uniform in solid angle (weight cos x solid angle) and from warped ones (divided by the density too).
// Both agree with the formula; the warped one with a fraction of the variance. (Where the normal points into a wide
// triangle whose corners all lie low, the cosine peaks inside it and a bilinear through the corners follows it
// less well; under the bunny's sky warping everywhere still measured 7-9% less error than sparing such triangles.)
TEST(Sampling, CosineWarpEstimatesTheProjectedSolidAngleWithLessVariance) {
  const Vec3 from(0.0f), p0(2.0f, -3.0f, 0.1f), p1(1.0f, 0.0f, 3.0f), p2(2.0f, 3.0f, 0.1f);
  const glm::dvec3 normal(0.0, 0.0, 1.0);
  const SphericalTriangle t = make_spherical_triangle(from, p0, p1, p2);
  ASSERT_GT(t.solid_angle, 1.0);  // a wide one: more than a sixth of the hemisphere
  const double exact =
      test::lambert_irradiance({glm::dvec3(p0), glm::dvec3(p1), glm::dvec3(p2)}, glm::dvec3(from), normal, 1.0);
  constexpr int kSamples = 200000;
  double sum[2] = {0, 0}, sum2[2] = {0, 0};
  Pcg32 rng(4, 4);
  for (int n = 0; n < kSamples; ++n) {
    const double u1 = rng.next_float(), u2 = rng.next_float();
    const double uniform = std::max(0.0, glm::dot(normal, sample_spherical_triangle(t, u1, u2))) * t.solid_angle;
    double w1 = u1, w2 = u2;
    const double density = warp_toward_cosine(t, normal, w1, w2);
    const double warped =
        std::max(0.0, glm::dot(normal, sample_spherical_triangle(t, w1, w2))) * t.solid_angle / density;
    sum[0] += uniform, sum2[0] += uniform * uniform;
    sum[1] += warped, sum2[1] += warped * warped;
  }
  double variance[2];
  for (int k = 0; k < 2; ++k) {
    const double m = sum[k] / kSamples;
    variance[k] = sum2[k] / kSamples - m * m;
    EXPECT_NEAR(m, exact, 4.0 * std::sqrt(variance[k] / kSamples) + 1e-9) << (k ? "warped" : "uniform");
  }
  EXPECT_LT(variance[1], 0.25 * variance[0]) << variance[0] << " against " << variance[1];
}

// The branch-free (cos, sin) of 2 pi u against libm in double: everywhere in [0, 1], at every quarter turn and on
// both sides of the points where the quadrant changes.
TEST(Sampling, CosSinOfATurnMatchesLibm) {
  std::vector<float> us = {0.0f, 1.0f, std::nextafter(1.0f, 0.0f)};
  for (int k = 0; k <= 8; ++k) {
    const float u = static_cast<float>(k) / 8.0f;
    for (const float v : {u, std::nextafter(u, 0.0f), std::nextafter(u, 2.0f)})
      if (v >= 0.0f && v <= 1.0f) us.push_back(v);
  }
  Pcg32 rng(5, 3);
  for (int i = 0; i < 1000000; ++i) us.push_back(rng.next_float());
  double worst = 0.0;
  for (const float u : us) {
    const Vec2 cs = cos_sin_2pi(u);
    const double angle = 2.0 * 3.14159265358979323846 * static_cast<double>(u);
    worst = std::max({worst, std::fabs(cs.x - std::cos(angle)), std::fabs(cs.y - std::sin(angle))});
  }
  // float's own rounding of values near 1 is 6e-8; the reduction and polynomials add less than that again.
  EXPECT_LT(worst, 2.5e-7) << "largest error " << worst;
}

// Cosine-weighted directions binned by (cos theta, phi): the probability of a bin is
// (cos^2 theta_0 - cos^2 theta_1) / 2 x (phi_1 - phi_0) / (2 pi) when integrating cos(theta)/pi over it.
TEST(Sampling, CosineHemisphereMatchesItsPdf) {
  constexpr int kThetaBins = 16, kPhiBins = 16, kSamples = 400000;
  std::vector<int> counts(kThetaBins * kPhiBins, 0);
  Pcg32 rng(2, 9);
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 d = sample_cosine_hemisphere(rng.next_float(), rng.next_float());
    ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
    ASSERT_GE(d.z, 0.0f);
    const float phi = std::atan2(d.y, d.x) + kPi;  // in [0, 2 pi]
    const int ti = std::min(static_cast<int>(d.z * kThetaBins), kThetaBins - 1);
    const int pi = std::min(static_cast<int>(phi / (2.0f * kPi) * kPhiBins), kPhiBins - 1);
    ++counts[static_cast<size_t>(ti * kPhiBins + pi)];
  }
  double chi2 = 0.0;
  for (int ti = 0; ti < kThetaBins; ++ti)
    for (int pi = 0; pi < kPhiBins; ++pi) {
      const double c0 = static_cast<double>(ti) / kThetaBins, c1 = static_cast<double>(ti + 1) / kThetaBins;
      const double p = (c1 * c1 - c0 * c0) / kPhiBins;  // cos-weighted mass of the bin
      const double expected = kSamples * p;
      const int count = counts[static_cast<size_t>(ti * kPhiBins + pi)];
      chi2 += (count - expected) * (count - expected) / expected;
    }
  EXPECT_FALSE(test::chi_square_rejects(chi2, kThetaBins * kPhiBins - 1)) << chi2;
  EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(1.0f), kInvPi);
  EXPECT_EQ(cosine_hemisphere_pdf(-0.1f), 0.0f);
}

// A scene whose emitters differ in area and radiance, so that the three strategies have distinct pmfs.
Scene make_mixed_lights_scene() { return make_default_scene(); }

class StrategyFrequencies : public ::testing::TestWithParam<LightStrategy> {};

TEST_P(StrategyFrequencies, MatchThePmf) {
  const Scene scene = make_mixed_lights_scene();
  const LightTable table = build_light_table(scene);
  ASSERT_GT(table.size(), 100u);
  const LightStrategy strategy = GetParam();

  double total_pmf = 0.0;
  for (uint32_t i = 0; i < table.size(); ++i) total_pmf += light_pmf(table, strategy, i);
  EXPECT_NEAR(total_pmf, 1.0, 1e-5);

  constexpr int kSamples = 2000000;
  std::vector<int> counts(table.size(), 0);
  Pcg32 rng(5, static_cast<uint64_t>(strategy));
  for (int i = 0; i < kSamples; ++i) {
    const LightChoice c = choose_light(table, strategy, rng.next_float());
    ASSERT_LT(c.index, table.size());
    ASSERT_FLOAT_EQ(c.pmf, light_pmf(table, strategy, c.index));
    ++counts[c.index];
  }
  double chi2 = 0.0;
  for (uint32_t i = 0; i < table.size(); ++i) {
    const double expected = kSamples * static_cast<double>(light_pmf(table, strategy, i));
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
  }
  EXPECT_FALSE(test::chi_square_rejects(chi2, static_cast<int>(table.size()) - 1)) << chi2;
}

INSTANTIATE_TEST_SUITE_P(Lights, StrategyFrequencies,
                         ::testing::Values(LightStrategy::kUniform, LightStrategy::kArea, LightStrategy::kPower),
                         test::strategy_test_name);

TEST(LightTable, SortedByDecreasingAreaWithConsistentPmfs) {
  const Scene scene = make_mixed_lights_scene();
  const LightTable table = build_light_table(scene);
  ASSERT_EQ(table.size(), scene.emitters.size());
  for (size_t i = 1; i < table.size(); ++i) EXPECT_GE(table.records[i - 1].area, table.records[i].area);
  // Area pmf is proportional to area; power pmf to area x luminance(Ke).
  const double total_area = table.by_area.cdf.back();
  for (uint32_t i = 0; i < table.size(); ++i) {
    EXPECT_NEAR(light_pmf(table, LightStrategy::kArea, i), table.records[i].area / total_area, 1e-6);
    EXPECT_NEAR(light_pmf(table, LightStrategy::kUniform, i), 1.0 / static_cast<double>(table.size()), 1e-9);
  }
  // The big ceiling triangles come first and are far more likely by area than uniformly.
  EXPECT_GT(light_pmf(table, LightStrategy::kArea, 0), 20.0f * light_pmf(table, LightStrategy::kUniform, 0));
}

TEST(LightTable, AlgorithmOnePicksExactlyWhatTheTablePicks) {
  const Scene scene = make_mixed_lights_scene();
  const LightTable table = build_light_table(scene);
  Pcg32 rng(11, 4);
  for (int i = 0; i < 200000; ++i) {
    const float u = rng.next_float();
    ASSERT_EQ(choose_light_linear_scan(table, u), choose_light(table, LightStrategy::kArea, u).index) << "u=" << u;
  }
  // Boundaries: u exactly at each cumulative step, and the extremes.
  for (uint32_t i = 0; i < table.size(); ++i) {
    const float u = static_cast<float>(table.by_area.cdf[i] / table.by_area.cdf.back());
    if (u >= 1.0f) continue;
    ASSERT_EQ(choose_light_linear_scan(table, u), choose_light(table, LightStrategy::kArea, u).index);
  }
  EXPECT_EQ(choose_light_linear_scan(table, 0.0f), 0u);
  EXPECT_EQ(choose_light(table, LightStrategy::kArea, std::nextafter(1.0f, 0.0f)).index, table.size() - 1);
}

// The table search against Algorithm 1's linear scan on tables of every size up to 40, with runs of equal
// cumulative values (zero-area emitters) and u at and around every step.
TEST(LightTable, TheSearchAgreesWithTheLinearScanOnEveryTableSize) {
  std::mt19937 random(3);
  for (size_t n = 1; n <= 40; ++n) {
    LightTable table;
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double area = random() % 4 == 0 && i > 0 ? 0.0 : 0.5 + static_cast<double>(random() % 100);
      sum += area;
      table.triangles.push_back(static_cast<uint32_t>(i));
      table.by_area.cdf.push_back(sum);
    }
    table.by_power = table.by_area;
    index_light_cdf(table.by_area);
    index_light_cdf(table.by_power);
    std::vector<float> us = {0.0f, std::nextafter(1.0f, 0.0f)};
    for (const double c : table.by_area.cdf) {
      const float u = static_cast<float>(c / sum);
      for (const float v : {u, std::nextafter(u, 0.0f), std::nextafter(u, 1.0f)})
        if (v >= 0.0f && v < 1.0f) us.push_back(v);
    }
    for (int i = 0; i < 2000; ++i) us.push_back(std::uniform_real_distribution<float>(0.0f, 1.0f)(random));
    for (const float u : us)
      ASSERT_EQ(choose_light(table, LightStrategy::kArea, u).index, choose_light_linear_scan(table, u))
          << n << " emitters, u = " << u;
  }
}

}  // namespace
}  // namespace lueur
