// The OBJ writer against the loader: a random scene survives a round trip bit for bit, and a loaded scene with the
// default light and default material survives a second trip unchanged. Uses the scene layer only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <array>
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

/// The float's bits: equal bits, not merely equal values (0 and -0 differ).
uint32_t bits(float x) {
  uint32_t b = 0;
  std::memcpy(&b, &x, 4);
  return b;
}

TEST(ObjWriter, NormalsTextureCoordinatesAndMapsRoundTripBitForBit) {
  // A cube with smooth normals computed on loading (a file without vn), and a textured quad with a cutout.
  Scene scene = load_obj_from_text(cube_obj(true), "", "cube.obj").scene;
  ASSERT_FALSE(scene.normals.empty());
  // Unit normals in every direction, as smoothing computes them: most are not exactly of length 1 in float, and
  // must read back with the bits they were written with, not divided by a length one ulp away from 1.
  std::mt19937 rng(7);
  std::normal_distribution<float> gaussian;
  for (int i = 0; i < 1000; ++i) scene.normals.push_back(glm::normalize(Vec3(gaussian(rng), gaussian(rng), gaussian(rng))));
  const uint32_t first_new = static_cast<uint32_t>(scene.positions.size());
  for (const Vec3& p : {Vec3(0, 3, 0), Vec3(1, 3, 0), Vec3(1, 3, 1), Vec3(0, 3, 1)}) scene.positions.push_back(p);
  for (const Vec2& t : {Vec2(0, 0), Vec2(2.5f, 0), Vec2(2.5f, 1.0f / 3.0f), Vec2(-0.0f, 1e-9f)})
    scene.texcoords.push_back(t);
  Material leaves;
  leaves.name = "leaves";
  leaves.diffuse_map = "textures/leaves.png";
  leaves.alpha_map = "textures/leaves mask.png";
  scene.materials.push_back(leaves);
  const uint32_t leaves_id = static_cast<uint32_t>(scene.materials.size() - 1);
  for (const auto& corners : {std::array<uint32_t, 3>{0, 1, 2}, std::array<uint32_t, 3>{0, 2, 3}}) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      t.v[k] = first_new + corners[static_cast<size_t>(k)];
      t.t[k] = corners[static_cast<size_t>(k)];
    }
    t.material = leaves_id;
    scene.triangles.push_back(t);
  }

  const std::string dir = test::make_temp_dir("writer-normals");
  write_obj(scene, dir + "/export.obj");
  const LoadedScene loaded = load_obj(dir + "/export.obj");
  const Scene& back = loaded.scene;
  ASSERT_EQ(back.normals.size(), scene.normals.size());
  for (size_t i = 0; i < scene.normals.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(bits(back.normals[i][k]), bits(scene.normals[i][k])) << "normal " << i << " component " << k;
  ASSERT_EQ(back.texcoords.size(), scene.texcoords.size());
  for (size_t i = 0; i < scene.texcoords.size(); ++i)
    for (int k = 0; k < 2; ++k)
      ASSERT_EQ(bits(back.texcoords[i][k]), bits(scene.texcoords[i][k])) << "texcoord " << i << " component " << k;
  ASSERT_EQ(back.triangles.size(), scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(back.triangles[i].v[k], scene.triangles[i].v[k]) << i;
      EXPECT_EQ(back.triangles[i].n[k], scene.triangles[i].n[k]) << i;
      EXPECT_EQ(back.triangles[i].t[k], scene.triangles[i].t[k]) << i;
    }
  const Material& maps = back.materials.at(leaves_id);
  EXPECT_EQ(maps.diffuse_map, "textures/leaves.png");
  EXPECT_EQ(maps.alpha_map, "textures/leaves mask.png");
  EXPECT_TRUE(has_warning(loaded, "leaves.png")) << "the map is named beside the export, where it is not";
}

}  // namespace
}  // namespace lueur
