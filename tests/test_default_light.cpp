// The default light the loader adds to scenes without emitters: where it is, which way it faces, and the irradiance
// it gives. Uses the scene layer only.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"

namespace lueur {
namespace {

using test::unit;

// ---- default light ----------------------------------------------------------------------------------------

/// Irradiance at `at` (normal +Y) from the scene's emitters, by midpoint integration over each triangle.
float irradiance_up(const Scene& scene, const Vec3& at) {
  double sum = 0.0;
  const int n = 200;
  for (uint32_t t : scene.emitters) {
    const float ke = scene.material_of(t).ke.r;
    const Vec3 light_normal = unit(scene.geometric_normal_raw(t));
    const double cell = scene.area(t) / (static_cast<double>(n) * n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n - i; ++j) {
        // Sub-triangles of a regular split: sample their centroids.
        for (int flip = 0; flip < (j < n - i - 1 ? 2 : 1); ++flip) {
          const float u = (static_cast<float>(i) + (flip ? 2.0f : 1.0f) / 3.0f) / static_cast<float>(n);
          const float v = (static_cast<float>(j) + (flip ? 2.0f : 1.0f) / 3.0f) / static_cast<float>(n);
          const Vec3 d = scene.point(t, u, v) - at;
          const float r2 = glm::dot(d, d);
          const float cos_receiver = std::max(0.0f, d.y / std::sqrt(r2));
          const float cos_light = std::max(0.0f, -glm::dot(light_normal, d) / std::sqrt(r2));
          sum += ke * cos_receiver * cos_light / r2 * cell;
        }
      }
    }
  }
  return static_cast<float>(sum);
}

TEST(DefaultLight, FacesDownAboveTheSceneAndLightsItAboutPi) {
  // A tall thin column: the light is small seen from the centre, so the point-light estimate is close.
  Scene scene;
  scene.positions = {Vec3(0, 0, 0), Vec3(0.1f, 0, 0), Vec3(0, 10, 0.1f)};
  scene.materials.push_back(Material{});
  scene.triangles.push_back(Triangle{});
  scene.triangles[0].v[1] = 1;
  scene.triangles[0].v[2] = 2;
  const Box3 box = scene.bounds();
  add_default_light(scene);
  ASSERT_EQ(scene.triangles.size(), 3u);
  EXPECT_EQ(scene.emitters, (std::vector<uint32_t>{1, 2}));
  const Material& light = scene.material_of(1);
  EXPECT_EQ(light.name, "lueur-default-light");
  EXPECT_EQ(light.kd, Vec3(0.0f));
  EXPECT_EQ(light.ke.r, light.ke.g);
  for (uint32_t t = 1; t < 3; ++t) EXPECT_NEAR(unit(scene.geometric_normal_raw(t)).y, -1.0f, 1e-6f);
  EXPECT_NEAR(scene.positions[scene.triangles[1].v[0]].y, box.hi.y + 0.5f * box.diagonal(), 1e-4f);
  EXPECT_NEAR(scene.area(1) + scene.area(2), 0.25f * box.diagonal() * box.diagonal(), 1e-3f);
  // The light is half as wide as it is far: the cosines cost about 8 percent against the point estimate.
  const float e = irradiance_up(scene, box.center());
  EXPECT_GT(e, 0.85f * kPi);
  EXPECT_LT(e, 1.0f * kPi);
}

TEST(DefaultLight, FlatSceneGetsRoughlyPi) {
  Scene scene = load_obj_from_text("v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nf 1 2 3 4\n", "", "floor.obj").scene;
  ASSERT_EQ(scene.emitters.size(), 2u);
  // The light is as wide as it is high here, so the cosines take their share: about 0.7 pi.
  const float e = irradiance_up(scene, Vec3(0.0f));
  EXPECT_GT(e, 0.6f * kPi);
  EXPECT_LT(e, 1.01f * kPi);
}

TEST(DefaultLight, ZeroSizeSceneStillGetsAFiniteLight) {
  Scene scene;
  scene.positions = {Vec3(3, 4, 5)};
  scene.materials.push_back(Material{});
  scene.triangles.push_back(Triangle{});  // all three corners on the one point
  add_default_light(scene);
  ASSERT_EQ(scene.emitters.size(), 2u);
  const Material& light = scene.material_of(scene.emitters[0]);
  EXPECT_TRUE(std::isfinite(light.ke.r));
  EXPECT_GT(light.ke.r, 0.0f);
  EXPECT_NEAR(scene.area(1) + scene.area(2), 0.25f, 1e-5f);
  EXPECT_NEAR(irradiance_up(scene, Vec3(3, 4, 5)), 0.75f * kPi, 0.05f * kPi);  // light as wide as high

  Scene empty;
  add_default_light(empty);
  EXPECT_EQ(empty.emitters.size(), 2u);
  EXPECT_TRUE(is_finite(empty.positions[0]));
}

}  // namespace
}  // namespace lueur
