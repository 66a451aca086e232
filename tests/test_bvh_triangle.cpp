// The ray-triangle test the BVH and its brute-force reference share (intersect_triangle): hits and barycentrics,
// the open interval, misses, parallel rays and zero-area triangles. Depends on bvh and core only.
#include <gtest/gtest.h>

#include <random>

#include "bvh/bvh.h"
#include "bvh_test_checks.h"
#include "bvh_test_scenes.h"

namespace lueur {
namespace {

using namespace lueur::test;  // the BVH suites' scenes, rays and checks

TEST(IntersectTriangle, HitsInsideAndReportsBarycentrics) {
  Ray ray;
  ray.origin = Vec3(0.25f, 0.25f, -2.0f);
  ray.dir = Vec3(0.0f, 0.0f, 1.0f);
  float t = -1.0f, u = -1.0f, v = -1.0f;
  ASSERT_TRUE(intersect_triangle(ray, Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
  EXPECT_FLOAT_EQ(u, 0.25f);
  EXPECT_FLOAT_EQ(v, 0.25f);
}

TEST(IntersectTriangle, RespectsOpenIntervalAndRejectsMissesAndParallelRays) {
  const Vec3 v0(0.0f), e1(1.0f, 0.0f, 0.0f), e2(0.0f, 1.0f, 0.0f);
  float t = 0.0f, u = 0.0f, v = 0.0f;
  Ray ray;
  ray.origin = Vec3(0.25f, 0.25f, -2.0f);
  ray.tmax = 2.0f;  // the hit is exactly at tmax: outside the open interval
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.tmax = kInfinity;
  ray.tmin = 2.0f;
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.tmin = 0.0f;
  ray.origin = Vec3(0.75f, 0.75f, -2.0f);  // beyond the hypotenuse
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.origin = Vec3(0.25f, 0.25f, 0.0f);  // in the plane, moving along it
  ray.dir = Vec3(1.0f, 0.0f, 0.0f);
  EXPECT_FALSE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  ray.origin = Vec3(0.25f, 0.25f, 2.0f);  // from behind: both faces count
  ray.dir = Vec3(0.0f, 0.0f, -1.0f);
  EXPECT_TRUE(intersect_triangle(ray, v0, e1, e2, t, u, v));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(IntersectTriangle, ZeroAreaTrianglesAreNeverHit) {
  // e1 == e2: the rounded determinant of Möller–Trumbore need not be zero, the prepared triangle makes it so.
  const Vec3 a(0.1f, 0.2f, 0.3f), b(0.7f, -0.4f, 1.3f);
  const BvhTriangle tri = make_bvh_triangle(a, b, b, 7);
  EXPECT_EQ(tri.id, 7u);
  EXPECT_EQ(tri.v0, a);
  std::mt19937 rng(5);
  for (int i = 0; i < 2000; ++i) {
    Ray ray;
    ray.origin = uniform_in(rng, Vec3(-2.0f), Vec3(2.0f));
    ray.dir = glm::mix(a, b, uniform(rng, 0.0f, 1.0f)) - ray.origin;
    float t = 0.0f, u = 0.0f, v = 0.0f;
    ASSERT_FALSE(intersect_triangle(ray, tri.v0, tri.e1, tri.e2, t, u, v)) << describe(ray);
  }
  const BvhTriangle normal = make_bvh_triangle(a, b, Vec3(1.0f, 1.0f, 1.0f), 0);
  EXPECT_EQ(normal.e1, b - a);
  EXPECT_EQ(normal.e2, Vec3(1.0f) - a);
}

}  // namespace
}  // namespace lueur
