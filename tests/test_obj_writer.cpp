// The OBJ writer against the loader: a random scene survives a round trip bit for bit, and a loaded scene with the
// default light and default material survives a second trip unchanged. Uses the scene layer only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/obj_writer.h"
#include "scene/scene.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::all_warnings;
using test::cube_obj;
using test::has_warning;

// ---- writer -----------------------------------------------------------------------------------------------

TEST(ObjWriter, RoundTripIsExact) {
  Scene scene;
  scene.name = "roundtrip";
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> mantissa(-1.0f, 1.0f);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 3000; ++i) {
    scene.positions.emplace_back(std::ldexp(mantissa(rng), exponent(rng)), std::ldexp(mantissa(rng), exponent(rng)),
                                 std::ldexp(mantissa(rng), exponent(rng)));
  }
  scene.positions.emplace_back(0.1f, 1.0f / 3.0f, -0.0f);
  scene.positions.emplace_back(16777217.0f, 3.4e38f, 1.17549435e-38f);
  Material a;
  a.name = "a";
  a.kd = Vec3(0.1f, 0.2f, 0.3f);
  Material b;
  b.name = "b-glossy";
  b.ks = Vec3(0.7f);
  b.ns = 1000.0f / 3.0f;
  Material light;
  light.name = "light";
  light.kd = Vec3(0.0f);
  light.ke = Vec3(17.0f, 12.0f, 4.0f);
  scene.materials = {a, b, light};
  std::uniform_int_distribution<uint32_t> vertex(0, static_cast<uint32_t>(scene.positions.size() - 1));
  for (int i = 0; i < 2000; ++i) {
    Triangle t;
    for (uint32_t& v : t.v) v = vertex(rng);
    t.material = static_cast<uint32_t>((i / 7) % 3);
    scene.triangles.push_back(t);
  }
  collect_emitters(scene);

  const std::string dir = test::make_temp_dir("writer");
  write_obj(scene, dir + "/out.obj");
  ASSERT_TRUE(test::file_exists(dir + "/out.mtl"));
  EXPECT_NE(test::read_file(dir + "/out.obj").find("mtllib out.mtl\n"), std::string::npos);
  const LoadedScene loaded = load_obj(dir + "/out.obj");
  const Scene& back = loaded.scene;
  EXPECT_EQ(back.name, "out");
  ASSERT_EQ(back.positions.size(), scene.positions.size());
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      uint32_t x = 0, y = 0;
      std::memcpy(&x, &scene.positions[i][k], 4);
      std::memcpy(&y, &back.positions[i][k], 4);
      ASSERT_EQ(x, y) << "position " << i << " component " << k << ": " << scene.positions[i][k];
    }
  }
  ASSERT_EQ(back.triangles.size(), scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) ASSERT_EQ(back.triangles[i].v[k], scene.triangles[i].v[k]);
    ASSERT_EQ(back.triangles[i].material, scene.triangles[i].material);
  }
  ASSERT_EQ(back.materials.size(), scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    EXPECT_EQ(back.materials[i].name, scene.materials[i].name);
    EXPECT_EQ(back.materials[i].kd, scene.materials[i].kd);
    EXPECT_EQ(back.materials[i].ks, scene.materials[i].ks);
    EXPECT_EQ(back.materials[i].ns, scene.materials[i].ns);
    EXPECT_EQ(back.materials[i].ke, scene.materials[i].ke);
  }
  EXPECT_EQ(back.emitters, scene.emitters);

  // A loaded scene (with its default light and default material) survives a second trip unchanged.
  write_obj(back, dir + "/again with space.obj");
  const Scene again = load_obj(dir + "/again with space.obj").scene;
  EXPECT_EQ(again.triangles.size(), back.triangles.size());
  EXPECT_EQ(again.materials.size(), back.materials.size());
}

TEST(ObjWriter, DefaultLightAndDefaultMaterialRoundTrip) {
  const Scene first = load_obj_from_text(cube_obj(false), "", "cube.obj").scene;
  const std::string dir = test::make_temp_dir("writer-default");
  write_obj(first, dir + "/cube.obj");
  const LoadedScene second = load_obj(dir + "/cube.obj");
  EXPECT_FALSE(has_warning(second, "no emitter")) << all_warnings(second);
  ASSERT_EQ(second.scene.triangles.size(), first.triangles.size());
  ASSERT_EQ(second.scene.materials.size(), first.materials.size());
  for (size_t i = 0; i < first.materials.size(); ++i) {
    EXPECT_EQ(second.scene.materials[i].name, first.materials[i].name);
    EXPECT_EQ(second.scene.materials[i].ke, first.materials[i].ke);
  }
  EXPECT_EQ(second.scene.emitters, first.emitters);
}

}  // namespace
}  // namespace lueur
