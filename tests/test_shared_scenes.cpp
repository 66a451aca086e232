// The real-world scenes in ../shared/scenes load with their documented triangle and emitter counts; each test
// skips where those scenes are absent. Uses the scene layer only.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::all_warnings;
using test::has_warning;
using test::unit;

// ---- shared real-world scenes -----------------------------------------------------------------------------

struct SharedScene {
  const char* file;
  size_t triangles;
  size_t emitters;
  bool default_light;
};

TEST(SharedScenes, LoadWithDocumentedCounts) {
  if (test::shared_scene("README.md").empty()) GTEST_SKIP() << "../shared/scenes not present";
  const SharedScene scenes[] = {
      {"cornell-original/CornellBox-Original.obj", 36, 2, false},
      {"cornell-glossy/CornellBox-Glossy.obj", 1112, 2, false},
      {"cornell-sphere/CornellBox-Sphere.obj", 2188, 2, false},
      {"cornell-water/CornellBox-Water.obj", 7088, 2, false},
      {"stanford-bunny/stanford-bunny.obj", 69451 + 12, 12, true},  // the light rig's sky
      {"conference/conference.obj", 331179 + 2, 2, true},           // a closed room: the rig's ceiling panel
  };
  for (const SharedScene& s : scenes) {
    SCOPED_TRACE(s.file);
    const std::string path = test::shared_scene(s.file);
    ASSERT_FALSE(path.empty());
    const auto start = std::chrono::steady_clock::now();
    const LoadedScene loaded = load_obj(path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ scene    ] %-45s %7zu triangles %zu emitters %.3f s\n%s", s.file, loaded.scene.triangles.size(),
                loaded.scene.emitters.size(), seconds, all_warnings(loaded).c_str());
    const Scene& scene = loaded.scene;
    EXPECT_EQ(scene.triangles.size(), s.triangles);
    EXPECT_EQ(scene.emitters.size(), s.emitters);
    EXPECT_EQ(has_warning(loaded, "no emitter"), s.default_light);
    for (uint32_t e : scene.emitters) EXPECT_GT(scene.area(e), 0.0f);
    if (s.default_light) {
      // The light rig's, after the model's triangles: a sky around the bunny, a ceiling panel in the closed room.
      for (uint32_t e : scene.emitters) {
        EXPECT_GE(e, scene.rig_begin);
        EXPECT_EQ(scene.material_of(e).name.rfind(s.emitters == 12 ? "lueur-sky-" : "lueur-room-light", 0), 0u);
      }
    }
    // Every shading normal is unit length and every index in range.
    for (const Vec3& n : scene.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
    for (const Triangle& t : scene.triangles) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_LT(t.v[c], scene.positions.size());
        ASSERT_TRUE(t.n[c] == kNoNormal || t.n[c] < scene.normals.size());
      }
      ASSERT_LT(t.material, scene.materials.size());
    }
  }
}

TEST(SharedScenes, CornellOriginalLightAndMaterials) {
  const std::string path = test::shared_scene("cornell-original/CornellBox-Original.obj");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes not present";
  const Scene scene = load_obj(path).scene;
  ASSERT_EQ(scene.emitters.size(), 2u);
  float area = 0.0f;
  for (uint32_t e : scene.emitters) {
    area += scene.area(e);
    EXPECT_EQ(scene.material_of(e).ke, Vec3(17.0f, 12.0f, 4.0f));
    EXPECT_NEAR(unit(scene.geometric_normal_raw(e)).y, -1.0f, 1e-5f);
  }
  EXPECT_NEAR(area, 0.1786f, 1e-3f);
}

TEST(SharedScenes, ConferenceZeroAreaTrianglesAreNeverEmitters) {
  const std::string path = test::shared_scene("conference/conference.obj");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes not present";
  const LoadedScene loaded = load_obj(path);
  size_t zero_area = 0;
  for (uint32_t t = 0; t < loaded.scene.triangles.size(); ++t) zero_area += !(loaded.scene.area(t) > 0.0f);
  EXPECT_GT(zero_area, 50000u);
  EXPECT_TRUE(has_warning(loaded, std::to_string(zero_area) + " zero-area triangles")) << all_warnings(loaded);
  EXPECT_EQ(loaded.scene.emitters.size(), 2u);
}

}  // namespace
}  // namespace lueur
