// The BVH's counted queries (intersect_closest / intersect_any with TraversalCounts): they answer what the plain
// queries answer and count the work they did. Depends on bvh and core only.
#include <gtest/gtest.h>

#include <random>

#include "bvh/bvh.h"
#include "bvh_test_checks.h"
#include "bvh_test_scenes.h"

namespace lueur {
namespace {

using namespace lueur::test;  // the BVH suites' scenes, rays and checks

TEST(Bvh, CountedQueriesAnswerTheSameAndCountTheirWork) {
  std::mt19937 rng(21);
  const Corners corners = make_soup(rng, 2000);
  const Bvh bvh = build_bvh(corners);
  const Box3 bounds = bounds_of(corners);
  TraversalCounts closest, any;
  constexpr int kRays = 2000;
  for (int i = 0; i < kRays; ++i) {
    const Ray ray = random_ray(rng, corners, bounds);
    const Hit expected = intersect_closest(bvh, ray);
    const Hit counted = intersect_closest(bvh, ray, closest);
    EXPECT_EQ(counted.triangle, expected.triangle);
    EXPECT_EQ(counted.t, expected.t);
    EXPECT_EQ(intersect_any(bvh, ray, any), intersect_any(bvh, ray));
  }
  for (const TraversalCounts& c : {closest, any}) {
    EXPECT_EQ(c.queries, static_cast<uint64_t>(kRays));
    EXPECT_GE(c.nodes, c.queries);  // the root at least
    EXPECT_GE(c.groups, c.leaves);
    EXPECT_GT(c.leaves, 0u);
  }

  // A ray that misses the scene's box tests the root's children and nothing else.
  TraversalCounts miss;
  Ray away;
  away.origin = bounds.hi + Vec3(1.0f);
  away.dir = Vec3(1.0f, 0.5f, 0.25f);
  EXPECT_FALSE(intersect_closest(bvh, away, miss).found());
  EXPECT_EQ(miss.nodes, 1u);
  EXPECT_EQ(miss.leaves, 0u);

  // A query on an empty tree is still a query, with no work.
  TraversalCounts empty;
  EXPECT_FALSE(intersect_closest(build_bvh(std::vector<Vec3>{}), away, empty).found());
  EXPECT_FALSE(intersect_any(build_bvh(std::vector<Vec3>{}), away, empty));
  EXPECT_EQ(empty.queries, 2u);
  EXPECT_EQ(empty.nodes, 0u);
}

}  // namespace
}  // namespace lueur
