// The `importance` light choice: clusters that hold their emitters, weights that never miss an emitter that can light
// the point, choices drawn as often as their pmf says, and the shadow rays it saves.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "integrator/direct_light.h"
#include "lights/light_lanes.h"
#include "lights/light_sampler.h"
#include "scene/default_scene.h"
#include "test_support.h"

namespace lueur {
namespace {

Vec3 random_direction(Pcg32& rng) {
  const float z = 2.0f * rng.next_float() - 1.0f, phi = 2.0f * kPi * rng.next_float();
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

/// `count` emitting triangles of random sizes, places and orientations in [-1, 1]^3, some tiny, some large, some
/// sharing a plane, and Ke of random brightness.
std::vector<EmitterRecord> random_emitters(int count, uint64_t seed) {
  Pcg32 rng(seed, 3);
  std::vector<EmitterRecord> records;
  for (int i = 0; i < count; ++i) {
    const Vec3 centre(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f);
    const float size = (i % 5 == 0 ? 0.6f : 0.05f) * (0.2f + rng.next_float());
    EmitterRecord e;
    // Every fourth in the plane y = 0.25, facing down, like panels of one ceiling.
    const Vec3 u = i % 4 == 0 ? Vec3(1.0f, 0.0f, 0.0f) : random_direction(rng);
    const Vec3 v = i % 4 == 0 ? Vec3(0.0f, 0.0f, 1.0f) : glm::normalize(glm::cross(u, random_direction(rng)));
    const Vec3 at = i % 4 == 0 ? Vec3(centre.x, 0.25f, centre.z) : centre;
    e.p0 = at;
    e.p1 = at + size * u;
    e.p2 = at + size * (0.3f * u + v);
    const Vec3 cross = glm::cross(e.p1 - e.p0, e.p2 - e.p0);
    e.area = 0.5f * glm::length(cross);
    e.normal = glm::normalize(cross);
    e.ke = Vec3(1.0f + 9.0f * rng.next_float(), 2.0f, 1.0f + 30.0f * rng.next_float() * rng.next_float());
    records.push_back(e);
  }
  return records;
}

TEST(LightClusters, HoldEveryEmitterOnceWithinTheirBounds) {
  for (const int count : {1, 5, 16, 17, 130}) {
    const std::vector<EmitterRecord> records = random_emitters(count, static_cast<uint64_t>(count));
    const LightClusters c = build_light_clusters(records);
    ASSERT_EQ(c.size(), std::min<size_t>(kMaxLightClusters, records.size())) << count;
    std::vector<int> seen(records.size(), 0);
    std::vector<double> powers;
    for (size_t k = 0; k < c.size(); ++k) {
      double share_sum = 0.0, power = 0.0;
      const Vec3 centre(c.cx[k], c.cy[k], c.cz[k]), axis(c.ax[k], c.ay[k], c.az[k]);
      for (uint32_t m = c.first[k]; m < c.first[k + 1]; ++m) {
        const uint32_t i = c.members[m];
        ++seen[i];
        EXPECT_EQ(c.cluster_of[i], k);
        share_sum += c.share[i];
        power += emitter_power(records[i]);
        const EmitterRecord& e = records[i];
        for (const Vec3& corner : {e.p0, e.p1, e.p2}) {
          EXPECT_LE(glm::length(corner - centre), c.radius[k]);
          EXPECT_LE(std::fabs(corner.x - centre.x), c.ex[k]);
          EXPECT_LE(std::fabs(corner.y - centre.y), c.ey[k]);
          EXPECT_LE(std::fabs(corner.z - centre.z), c.ez[k]);
          EXPECT_GE(glm::dot(axis, corner), c.lowest[k]);
        }
        EXPECT_GE(glm::dot(axis, e.normal), c.cos_spread[k]);
        EXPECT_LE(glm::length(e.normal - axis), c.tilt[k]);
      }
      EXPECT_NEAR(share_sum, 1.0, 1e-5);
      powers.push_back(power);
    }
    // Powers relative to the brightest cluster's.
    const double brightest = *std::max_element(powers.begin(), powers.end());
    for (size_t k = 0; k < c.size(); ++k) EXPECT_NEAR(c.power[k], powers[k] / brightest, 1e-5);
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "emitter " << i << " of " << count;
  }
}

// The weight may be loose but never zero where some point of some emitter of the cluster can light the point: points
// all over each emitter (corners, edges, inside) are tried from random points and normals, among and around the
// emitters.
TEST(LightClusters, NeverWeighNothingWhereAnEmitterCanLightThePoint) {
  // 60 emitters (clusters of a few, chosen by power) and 400 (clusters large enough to choose by their trees).
  for (const int count : {60, 400}) {
    const std::vector<EmitterRecord> records = random_emitters(count, 11);
    const LightClusters c = build_light_clusters(records);
    EXPECT_EQ(c.tree.empty(), count == 60);
    Pcg32 rng(42, 1);
    const int trials = 180000 / count;
    int zero_weights = 0, checked = 0;
    for (int trial = 0; trial < trials; ++trial) {
      const Vec3 p(2.4f * rng.next_float() - 1.2f, 2.4f * rng.next_float() - 1.2f, 2.4f * rng.next_float() - 1.2f);
      const Vec3 n = random_direction(rng);
      LightWeights w;
      weigh_light_clusters(c, p, n, w);
      for (uint32_t i = 0; i < records.size(); ++i) {
        const EmitterRecord& e = records[i];
        const float pmf = weighted_light_pmf(c, w, i);
        if (pmf > 0.0f) continue;
        ++zero_weights;
        for (int s = 0; s < 64; ++s) {
          const Vec2 b = s < 3 ? Vec2(s == 1, s == 2) : sample_uniform_triangle(rng.next_float(), rng.next_float());
          const Vec3 x = (1.0f - b.x - b.y) * e.p0 + b.x * e.p1 + b.y * e.p2;
          const Vec3 wi = glm::normalize(x - p);
          const float cos_surface = glm::dot(n, wi), cos_light = -glm::dot(e.normal, wi);
          ++checked;
          ASSERT_FALSE(cos_surface > 1e-4f && cos_light > 1e-4f)
              << "emitter " << i << " of " << count << " lights the point with cosines " << cos_surface << ", "
              << cos_light << " yet weighs nothing";
        }
      }
    }
    // The test must have tried cases: about half the emitters are behind the horizon or face away.
    EXPECT_GT(zero_weights, trials * count / 4);
    EXPECT_GT(checked, 0);
  }
}

TEST(LightClusters, ChoicesComeAsOftenAsTheirPmfSays) {
  const Scene scene = make_default_scene();
  const LightTable table = build_light_table(scene);
  // A point on the floor, one on the left wall, one on the back wall beside the wall lamp.
  const std::vector<std::pair<Vec3, Vec3>> points = {{Vec3(300.0f, 0.0f, 300.0f), Vec3(0.0f, 1.0f, 0.0f)},
                                                     {Vec3(550.0f, 300.0f, 300.0f), Vec3(-1.0f, 0.0f, 0.0f)},
                                                     {Vec3(260.0f, 430.0f, 559.2f), Vec3(0.0f, 0.0f, -1.0f)}};
  for (const auto& [position, normal] : points) {
    LightWeights w;
    weigh_light_clusters(table.clusters, position, normal, w);
    ASSERT_GT(w.total, 0.0f);
    double total_pmf = 0.0;
    for (uint32_t i = 0; i < table.size(); ++i) total_pmf += weighted_light_pmf(table.clusters, w, i);
    EXPECT_NEAR(total_pmf, 1.0, 1e-5);
    constexpr int kSamples = 1000000;
    std::vector<int> counts(table.size(), 0);
    Pcg32 rng(7, static_cast<uint64_t>(position.x));
    for (int s = 0; s < kSamples; ++s) {
      const LightChoice choice = choose_weighted_light(table.clusters, w, rng.next_float());
      ASSERT_LT(choice.index, table.size());
      ASSERT_FLOAT_EQ(choice.pmf, weighted_light_pmf(table.clusters, w, choice.index));
      ++counts[choice.index];
    }
    double chi2 = 0.0;
    int dof = -1;
    for (uint32_t i = 0; i < table.size(); ++i) {
      const double expected = kSamples * static_cast<double>(weighted_light_pmf(table.clusters, w, i));
      if (expected == 0.0) {
        EXPECT_EQ(counts[i], 0) << "emitter " << i << " has pmf 0 yet was chosen";
        continue;
      }
      chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
      ++dof;
    }
    EXPECT_FALSE(test::chi_square_rejects(chi2, dof)) << chi2 << " at " << position.x << ", " << position.y;
  }
}

// The choice inverts the two-level cdf exactly as a plain scan would: the first cluster whose running weight exceeds
// u x total, then the first member whose running power exceeds its share of it. Checked against that scan (written
// out here) at random numbers and at the edges (0, just below 1, and exactly on the clusters' boundaries), over
// clusters of one to sixteen members (larger ones choose by a tree, tested below).
TEST(LightClusters, ChoicesInvertTheirCdfAsAScanWould) {
  // Random emitters, and 64 equal ones in a row (clusters of equal members, whose running powers 1, 2, 3... a number
  // lands on exactly).
  std::vector<EmitterRecord> equal;
  for (int i = 0; i < 64; ++i) {
    EmitterRecord e;
    e.p0 = Vec3(0.1f * static_cast<float>(i), 1.0f, 0.0f);
    e.p1 = e.p0 + Vec3(0.05f, 0.0f, 0.0f);
    e.p2 = e.p0 + Vec3(0.0f, 0.0f, 0.05f);
    e.area = 0.00125f;
    e.normal = Vec3(0.0f, -1.0f, 0.0f);
    e.ke = Vec3(4.0f);
    equal.push_back(e);
  }
  int checked = 0;
  for (const std::vector<EmitterRecord>& records : {random_emitters(200, 11), equal}) {
    const LightClusters c = build_light_clusters(records);
    ASSERT_EQ(c.size(), kMaxLightClusters);
    auto scan = [&](const LightWeights& w, float u) {
      const float x = u * w.total;
      size_t k = 0;
      while (k + 1 < c.size() && !(w.cdf[k] > x)) ++k;
      while (!(w.weight[k] > 0.0f)) --k;
      const double v = std::clamp(static_cast<double>((x - (w.cdf[k] - w.weight[k])) / w.weight[k]), 0.0, 1.0);
      const double target = v * c.member_cdf[c.first[k + 1] - 1];
      size_t m = c.first[k];
      while (m + 1 < c.first[k + 1] && !(c.member_cdf[m] > target)) ++m;
      return std::pair<size_t, uint32_t>(k, c.members[m]);
    };
    Pcg32 rng(5, 9);
    for (int point = 0; point < 200; ++point) {
      LightWeights w;
      weigh_light_clusters(c, random_direction(rng) * 3.0f, random_direction(rng), w);
      if (!(w.total > 0.0f)) continue;
      std::vector<float> us = {0.0f, std::nextafter(1.0f, 0.0f), 0.5f};
      for (size_t k = 0; k < c.size(); ++k)
        for (const float within : {0.0f, 0.125f, 0.25f, 0.5f, 0.75f, 1.0f})
          us.push_back((w.cdf[k] - w.weight[k] + within * w.weight[k]) / w.total);
      for (int i = 0; i < 200; ++i) us.push_back(rng.next_float());
      for (const float u : us) {
        if (!(u < 1.0f)) continue;
        const auto [cluster, member] = scan(w, u);
        const LightChoice choice = choose_weighted_light(c, w, u);
        const uint32_t chosen = choice.index;
        // A cluster with a tree chooses its member by the tree (tested below; pmf 0 where no node in it can light
        // the point); the cluster is chosen the same way.
        if (c.root[cluster] != kNoTreeNode) {
          if (choice.pmf > 0.0f) {
            ASSERT_EQ(c.cluster_of[chosen], cluster) << "u = " << u << " at point " << point;
          }
          continue;
        }
        ASSERT_EQ(chosen, member) << "u = " << u << " at point " << point;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20000);
}

// In clusters too large to choose by power, the tree's choices come as often as weighted_light_pmf says, and the
// samples that find no emitter (every node below a cluster's cut weighing nothing) as often as the pmfs fall short
// of 1.
TEST(LightClusters, TreeChoicesComeAsOftenAsTheirPmfSays) {
  const std::vector<EmitterRecord> records = random_emitters(400, 3);
  const LightClusters c = build_light_clusters(records);
  ASSERT_FALSE(c.tree.empty());
  const std::vector<std::pair<Vec3, Vec3>> points = {{Vec3(0.0f, -1.5f, 0.0f), Vec3(0.0f, 1.0f, 0.0f)},
                                                     {Vec3(0.3f, 0.2f, -0.4f), glm::normalize(Vec3(1.0f, 1.0f, 0.0f))},
                                                     {Vec3(0.9f, 0.9f, 0.9f), glm::normalize(Vec3(-1.0f))}};
  for (const auto& [position, normal] : points) {
    LightWeights w;
    weigh_light_clusters(c, position, normal, w);
    ASSERT_GT(w.total, 0.0f);
    std::vector<double> expected(records.size() + 1, 0.0);  // the last: no emitter
    double total_pmf = 0.0;
    for (uint32_t i = 0; i < records.size(); ++i) total_pmf += expected[i] = weighted_light_pmf(c, w, i);
    ASSERT_LT(total_pmf, 1.0 + 1e-5);
    expected.back() = std::max(0.0, 1.0 - total_pmf);
    constexpr int kSamples = 1000000;
    std::vector<int> counts(records.size() + 1, 0);
    Pcg32 rng(17, static_cast<uint64_t>(position.y * 100.0f + 500.0f));
    for (int s = 0; s < kSamples; ++s) {
      const LightChoice choice = choose_weighted_light(c, w, rng.next_float());
      if (!(choice.pmf > 0.0f)) {
        ++counts.back();
        continue;
      }
      ASSERT_LT(choice.index, records.size());
      ASSERT_FLOAT_EQ(choice.pmf, weighted_light_pmf(c, w, choice.index));
      ++counts[choice.index];
    }
    // Bins expected fewer than 5 times pooled into one, as the chi-square test needs.
    double chi2 = 0.0, pooled_expected = 0.0;
    int pooled_count = 0, dof = -1;
    for (size_t i = 0; i < expected.size(); ++i) {
      const double e = kSamples * expected[i];
      if (e == 0.0) {
        EXPECT_EQ(counts[i], 0) << "emitter " << i << " has pmf 0 yet was chosen";
        continue;
      }
      if (e < 5.0) {
        pooled_expected += e, pooled_count += counts[i];
        continue;
      }
      chi2 += (counts[i] - e) * (counts[i] - e) / e;
      ++dof;
    }
    if (pooled_expected > 0.0) {
      chi2 += (pooled_count - pooled_expected) * (pooled_count - pooled_expected) / pooled_expected;
      ++dof;
    }
    EXPECT_GT(dof, 50);
    EXPECT_FALSE(test::chi_square_rejects(chi2, dof)) << chi2 << " for " << dof << " at " << position.y;
  }
}

// The AVX2 build of a tree node's weighing gives the baseline build's bits: the image must not depend on the CPU.
// Points near, among and far from the emitters, against every node.
TEST(LightClusters, TreeNodesWeighTheSameBitsWithAvx2AsWithout) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this CPU has no AVX2: only the baseline build runs here";
  const LightClusters c = build_light_clusters(random_emitters(400, 7));
  ASSERT_FALSE(c.tree.empty());
  Pcg32 rng(3, 4);
  int lanes = 0, positive = 0;
  for (int point = 0; point < 400; ++point) {
    const ImportanceQuery q(random_direction(rng) * (0.05f + 3.0f * rng.next_float()), random_direction(rng));
    for (const LightTreeNode& node : c.tree) {
      std::array<float, kLightTreeWidth> baseline, avx2;
      weigh_tree_children_baseline(node, q, baseline.data());
      weigh_tree_children_avx2(node, q, avx2.data());
      ASSERT_EQ(std::memcmp(baseline.data(), avx2.data(), sizeof baseline), 0) << "at point " << point;
      for (const float w : baseline) positive += w > 0.0f;
      lanes += static_cast<int>(kLightTreeWidth);
    }
  }
  EXPECT_GT(positive, lanes / 10) << "the weights compared are mostly zero";
}

// Weights past a float's range (a point a hair from a speck of an emitter) say so, and L1 then chooses by power;
// ordinary ones do not.
TEST(LightClusters, SayWhenTheirWeightsOverflow) {
  EmitterRecord speck;
  speck.p0 = Vec3(0.0f), speck.p1 = Vec3(1e-21f, 0.0f, 0.0f), speck.p2 = Vec3(0.0f, 1e-21f, 0.0f);
  speck.normal = Vec3(0.0f, 0.0f, 1.0f), speck.ke = Vec3(1.0f), speck.area = 0.5e-42f;
  ASSERT_GT(speck.area, 0.0f);
  const LightClusters c = build_light_clusters({speck});
  LightWeights w;
  // Inside its bounding sphere: power / radius^2, with a radius under 1e-21.
  weigh_light_clusters(c, Vec3(0.0f, 0.0f, 1e-22f), Vec3(0.0f, 0.0f, -1.0f), w);
  EXPECT_TRUE(w.overflowed);
  EXPECT_EQ(w.total, 0.0f);
  weigh_light_clusters(c, Vec3(0.0f, 0.0f, 0.5f), Vec3(0.0f, 0.0f, -1.0f), w);
  EXPECT_FALSE(w.overflowed);
  EXPECT_GT(w.total, 0.0f);
}

// The ceiling light hangs 0.5 mm under the ceiling and the wall lamp 0.5 mm in front of the back wall: from the
// ceiling nothing reaches the ceiling light, from the back wall nothing reaches the lamp, and from a lamp triangle
// nothing reaches the lamp's other triangles. `importance` spends no shadow ray there; `area` does.
TEST(LightClusters, SpendNoShadowRayOnAnEmitterThatCannotLightThePoint) {
  Scene scene = make_default_scene();
  const auto traced = prepare_scene(std::move(scene));
  const LightTable& table = traced->lights;
  const auto weigh = [&](const Vec3& position, const Vec3& normal) {
    LightWeights w;
    weigh_light_clusters(table.clusters, position, normal, w);
    double ceiling_light = 0.0, lamp = 0.0;
    for (uint32_t i = 0; i < table.size(); ++i)
      (table.records[i].normal.y < -0.5f ? ceiling_light : lamp) += weighted_light_pmf(table.clusters, w, i);
    return std::pair{ceiling_light, lamp};
  };
  const auto [ceiling_from_ceiling, lamp_from_ceiling] = weigh(Vec3(278.0f, 548.8f, 280.0f), Vec3(0, -1, 0));
  EXPECT_EQ(ceiling_from_ceiling, 0.0);
  EXPECT_NEAR(lamp_from_ceiling, 1.0, 1e-6);
  const auto [ceiling_from_wall, lamp_from_wall] = weigh(Vec3(150.0f, 430.0f, 559.2f), Vec3(0, 0, -1));
  EXPECT_NEAR(ceiling_from_wall, 1.0, 1e-6);
  EXPECT_EQ(lamp_from_wall, 0.0);
  const auto [ceiling_from_lamp, lamp_from_lamp] = weigh(Vec3(150.0f, 430.0f, 558.7f), Vec3(0, 0, -1));
  EXPECT_NEAR(ceiling_from_lamp, 1.0, 1e-6);
  EXPECT_EQ(lamp_from_lamp, 0.0);

  // On the ceiling, beside the light: only the lamp can light it; with `area` 58% of the samples go to the ceiling
  // light and trace no ray (the point is behind it), with `importance` every sample goes to the lamp and traces one.
  Ray up;
  up.origin = Vec3(400.0f, 300.0f, 450.0f);
  up.dir = Vec3(0.0f, 1.0f, 0.0f);
  const Hit hit = intersect_closest(traced->accel, up);
  ASSERT_TRUE(hit.found());
  const SurfacePoint ceiling_point = make_surface_point(traced->scene, up, hit);
  ASSERT_NEAR(ceiling_point.position.y, 548.8f, 1e-3f);
  uint64_t area_rays = 0, importance_rays = 0;
  DirectLightOptions options;
  options.rays = 16;
  PixelSampler sampler(SamplerKind::kSobol, 1, 2, 3, RngPurpose::kRecompute);
  Vec3 area_sum(0.0f), importance_sum(0.0f);
  for (int s = 0; s < 256; ++s) {
    options.strategy = LightStrategy::kArea;
    area_sum += estimate_direct_light(*traced, ceiling_point, options, sampler, 16u * s, area_rays);
    options.strategy = LightStrategy::kImportance;
    importance_sum += estimate_direct_light(*traced, ceiling_point, options, sampler, 16u * s, importance_rays);
  }
  EXPECT_EQ(importance_rays, 16u * 256u);
  EXPECT_LT(area_rays, 0.6 * 16 * 256);
  EXPECT_NEAR(luminance(importance_sum), luminance(area_sum), 0.05 * luminance(area_sum));
}

}  // namespace
}  // namespace lueur
