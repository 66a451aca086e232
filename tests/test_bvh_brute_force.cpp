// Lueur's BVH against a brute-force loop over every triangle: closest and any hit on many rays over several scenes
// (soups, grids, slivers, copies, stars, spheres; a large one built with parallel binning; the 4-wide SSE tree on
// any machine), with the tree's invariants checked on each. Depends on bvh and core only.
#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "bvh/bvh.h"
#include "bvh_test_checks.h"
#include "bvh_test_scenes.h"
#include "test_support.h"

namespace lueur {
namespace {

using namespace lueur::test;  // the BVH suites' scenes, rays and checks

struct SceneCase {
  const char* name;
  Corners corners;
  size_t rays;
};

void run_scene(const SceneCase& scene, uint32_t seed) {
  const Bvh bvh = build_bvh(scene.corners);
  const uint32_t depth = check_invariants(bvh, scene.corners);
  const RayStats stats = compare_with_brute_force(scene.corners, bvh, scene.rays, seed);
  std::cout << "[ scene    ] " << scene.name << ": " << scene.corners.size() / 3 << " triangles, " << bvh.nodes.size()
            << " nodes, depth " << depth << ", " << stats.rays << " rays, " << stats.hits << " hits, "
            << stats.misses_bounded_below << " misses that must test nodes below the root\n";
  // Both outcomes must be well represented, or the comparison proves little.
  EXPECT_GT(stats.hits, stats.rays / 10) << scene.name;
  EXPECT_LT(stats.hits, stats.rays - stats.rays / 20) << scene.name;
}

// Rays compared with brute force per scene. CTest runs each test in its own process, so the total is checked
// at compile time rather than by counting at run time (run_scene asserts that each scene traced its count).
constexpr size_t kSoupRays = 25000, kFlatGridRays = 15000, kHeightFieldRays = 15000, kSliverRays = 20000,
                 kCopiesRays = 10000, kSphereRays = 20000, kStarRays = 5000;
static_assert(kSoupRays + kFlatGridRays + kHeightFieldRays + kSliverRays + kCopiesRays + kSphereRays + kStarRays >=
                  100000,
              "the BVH must be checked against brute force on at least 100k rays");

TEST(BvhVersusBruteForce, RandomSoup) {
  std::mt19937 rng(1);
  run_scene({"soup", make_soup(rng, 2000), kSoupRays}, 101);
}

TEST(BvhVersusBruteForce, FlatGrid) { run_scene({"flat grid", make_grid(48, true), kFlatGridRays}, 102); }

TEST(BvhVersusBruteForce, HeightFieldGrid) { run_scene({"height field", make_grid(48, false), kHeightFieldRays}, 103); }

TEST(BvhVersusBruteForce, SliversAndDegenerates) {
  std::mt19937 rng(2);
  const Corners corners = make_slivers(rng);
  ASSERT_GE(count_zero_area(corners), 240u);
  run_scene({"slivers", corners, kSliverRays}, 104);
  // Zero-area triangles never win, even when rays are aimed straight at them.
  const Bvh bvh = build_bvh(corners);
  std::mt19937 ray_rng(5);
  const Box3 bounds = bounds_of(corners);
  for (int i = 0; i < 5000; ++i) {
    const Hit hit = intersect_closest(bvh, random_ray(ray_rng, corners, bounds));
    if (!hit.found()) continue;
    const size_t k = hit.triangle;
    ASSERT_NE(glm::cross(corners[3 * k + 1] - corners[3 * k], corners[3 * k + 2] - corners[3 * k]), Vec3(0.0f));
  }
}

TEST(BvhVersusBruteForce, ThousandCopiesOfOneTriangle) {
  Corners corners;
  for (int i = 0; i < 1000; ++i)
    add_triangle(corners, Vec3(-1.0f, -1.0f, 0.0f), Vec3(1.0f, -1.0f, 0.2f), Vec3(0.0f, 1.0f, -0.3f));
  run_scene({"copies", corners, kCopiesRays}, 105);
  const Bvh bvh = build_bvh(corners);
  std::mt19937 rng(6);
  const Box3 bounds = bounds_of(corners);
  for (int i = 0; i < 2000; ++i) {
    const Hit hit = intersect_closest(bvh, random_ray(rng, corners, bounds));
    if (hit.found()) {
      ASSERT_EQ(hit.triangle, 0u);
    }
  }
}

TEST(BvhVersusBruteForce, StarOfOverlappingSlivers) {
  std::mt19937 rng(12);
  run_scene({"star", make_star(rng, 3000), kStarRays}, 110);
}

TEST(BvhVersusBruteForce, ClosedSphere) { run_scene({"sphere", make_sphere(40, 80, 3.0f), kSphereRays}, 106); }

// Above 65536 triangles the top of the tree bins and bounds its nodes on several threads (one slice each): the
// slices' merged bins must give a correct tree.
TEST(BvhVersusBruteForce, LargeSphereBuiltWithParallelBinning) {
  const Corners corners = make_sphere(160, 320, 3.0f);
  ASSERT_GT(corners.size() / 3, 100000u);
  run_scene({"large sphere", corners, 2000}, 107);
}

// The tests above trace the tree this CPU gets (8-wide AVX2 when it has AVX2); these check the 4-wide SSE kernels,
// which CPUs without AVX2 run, against brute force on any machine.
TEST(BvhVersusBruteForce, SseKernelsOnAnyMachine) {
  std::mt19937 rng(7);
  const Corners soup = make_soup(rng, 2000);
  const Corners sphere = make_sphere(40, 80, 3.0f);
  const Bvh default_soup = build_bvh(soup);
  EXPECT_EQ(default_soup.wide8_nodes.empty(), !bvh_avx2_enabled());
  Bvh sse_soup, sse_sphere;
  {
    const test::ScopedEnv isa("LUEUR_BVH_ISA", "sse");  // restored even if a build throws
    sse_soup = build_bvh(soup);
    sse_sphere = build_bvh(sphere);
  }
  ASSERT_TRUE(sse_soup.wide8_nodes.empty());
  ASSERT_FALSE(sse_soup.wide_nodes.empty());
  const RayStats a = compare_with_brute_force(soup, sse_soup, 10000, 108);
  const RayStats b = compare_with_brute_force(sphere, sse_sphere, 10000, 109);
  EXPECT_GT(a.hits + b.hits, (a.rays + b.rays) / 10);
}

}  // namespace
}  // namespace lueur
