// The BVH on empty and degenerate inputs: no triangles, non-finite ones, 100000 copies of one triangle, point
// triangles and geometrically growing sizes. Each must build a tree that keeps its invariants and answers as the
// brute-force loop does. Depends on bvh and core only.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "bvh/bvh.h"
#include "bvh_test_checks.h"
#include "bvh_test_scenes.h"

namespace lueur {
namespace {

using namespace lueur::test;  // the BVH suites' scenes, rays and checks

TEST(Bvh, EmptyInputGivesNoHits) {
  const Bvh bvh = build_bvh(std::vector<Vec3>{});
  EXPECT_TRUE(bvh.empty());
  Ray ray;
  EXPECT_FALSE(intersect_closest(bvh, ray).found());
  EXPECT_EQ(intersect_closest(bvh, ray).t, kInfinity);
  EXPECT_FALSE(intersect_any(bvh, ray));
}

TEST(Bvh, NonFiniteTrianglesAreDropped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Corners only_bad;
  add_triangle(only_bad, Vec3(nan, 0.0f, 0.0f), Vec3(1.0f), Vec3(2.0f, 0.0f, 1.0f));
  add_triangle(only_bad, Vec3(0.0f), Vec3(kInfinity, 1.0f, 0.0f), Vec3(0.0f, 1.0f, 1.0f));
  const Bvh empty = build_bvh(only_bad);
  EXPECT_TRUE(empty.empty());
  EXPECT_FALSE(intersect_any(empty, Ray{}));

  std::mt19937 rng(11);
  Corners corners = make_soup(rng, 600);
  for (size_t i = 0; i < corners.size(); i += 37) corners[i][static_cast<int>(i % 3)] = (i % 2 == 0) ? nan : -kInfinity;
  const Bvh bvh = build_bvh(corners);
  check_invariants(bvh, corners);
  const RayStats stats = compare_with_brute_force(corners, bvh, 5000, 12);
  EXPECT_GT(stats.hits, stats.rays / 5);
}

TEST(Bvh, IdenticalTrianglesBuildAndTieToLowestIndex) {
  Corners corners;
  for (int i = 0; i < 100000; ++i) {
    add_triangle(corners, Vec3(-1.0f, -1.0f, 0.5f), Vec3(1.5f, -0.5f, 0.25f), Vec3(0.0f, 2.0f, -0.5f));
  }
  const Bvh bvh = build_bvh(corners);
  const uint32_t depth = check_invariants(bvh, corners);
  EXPECT_LE(depth, 20u);  // a median split halves each time
  std::mt19937 rng(3);
  size_t hits = 0;
  // Few rays: with every copy at the same distance, each hit has to look at all 100k triangles.
  for (int i = 0; i < 300; ++i) {
    Ray ray;
    ray.origin = uniform_in(rng, Vec3(-3.0f), Vec3(3.0f));
    ray.dir = Vec3(uniform(rng, -1.0f, 1.0f), uniform(rng, -1.0f, 1.0f), 0.0f) - ray.origin;
    const Hit hit = intersect_closest(bvh, ray);
    if (hit.found()) {
      ++hits;
      ASSERT_EQ(hit.triangle, 0u) << describe(ray);
    }
    float t = 0.0f, u = 0.0f, v = 0.0f;
    const BvhTriangle& tri = bvh.triangles.front();
    ASSERT_EQ(intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v), hit.found()) << describe(ray);
    if (hit.found()) {
      ASSERT_EQ(hit.t, t);
    }
    ASSERT_EQ(intersect_any(bvh, ray), hit.found());
  }
  EXPECT_GT(hits, 30u);
}

TEST(Bvh, PointTrianglesBuildAndAreNeverHit) {
  Corners corners;
  for (int i = 0; i < 100000; ++i) add_triangle(corners, Vec3(0.5f), Vec3(0.5f), Vec3(0.5f));
  const Bvh bvh = build_bvh(corners);
  check_invariants(bvh, corners);
  Ray ray;
  ray.origin = Vec3(0.5f, 0.5f, -1.0f);
  EXPECT_FALSE(intersect_closest(bvh, ray).found());
  EXPECT_FALSE(intersect_any(bvh, ray));
}

TEST(Bvh, GeometricallyGrowingTrianglesStayWithinTheDepthBound) {
  // Each triangle dwarfs all the previous ones, which invites SAH to peel them off one at a time.
  Corners corners;
  float s = 1.0f;
  for (int i = 0; i < 600; ++i, s *= 1.08f) {
    add_triangle(corners, Vec3(s, 0.0f, 0.0f), Vec3(1.5f * s, 0.3f * s, 0.1f * s), Vec3(1.2f * s, -0.2f * s, 0.4f * s));
  }
  const Bvh bvh = build_bvh(corners);
  const uint32_t depth = check_invariants(bvh, corners);
  std::cout << "[ depth    ] " << depth << "\n";
  EXPECT_LT(depth, kBvhMaxDepth);
  compare_with_brute_force(corners, bvh, 3000, 21);
}

}  // namespace
}  // namespace lueur
