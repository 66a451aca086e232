// The OBJ loader's conversion into Scene: triangulation and winding, materials and emitters, file normals, and the
// warnings for what it repaired (missing MTL, unknown materials, bad material values).
// Uses the scene layer only (no BVH, no renderer).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::all_warnings;
using test::count_with_material;
using test::flat_shading;
using test::has_warning;
using test::kTriangle;
using test::unit;
using test::write_text;

// ---- basic geometry ---------------------------------------------------------------------------------------

TEST(SceneLoader, QuadBecomesTwoCounterClockwiseTriangles) {
  // Counter-clockwise seen from +Y: both triangles must face +Y and together cover the unit square.
  const LoadedScene loaded =
      load_obj_from_text("v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nf 1 2 3 4\n", "", "quad.obj", flat_shading());
  const Scene& scene = loaded.scene;
  EXPECT_EQ(scene.name, "quad");
  // The default light rig adds the twelve triangles of its sky after the quad.
  ASSERT_EQ(scene.triangles.size(), 14u);
  EXPECT_EQ(scene.rig_begin, 2u);
  float area = 0.0f;
  for (uint32_t t = 0; t < 2; ++t) {
    const Vec3 n = unit(scene.geometric_normal_raw(t));
    EXPECT_NEAR(n.y, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(scene.shading_normal(t, 0.3f, 0.3f), n), 1.0f, 1e-6f);  // no normals: geometric
    area += scene.area(t);
  }
  EXPECT_NEAR(area, 1.0f, 1e-6f);
  const Box3 box = scene.bounds();
  EXPECT_EQ(box.hi.y, 0.0f);  // the model's: the light rig is left out
  EXPECT_EQ(box.hi.x, 1.0f);
  EXPECT_NEAR(scene.point(0, 0.0f, 0.0f).x, scene.positions[scene.triangles[0].v[0]].x, 0.0f);
}

TEST(SceneLoader, MaterialsAndEmitters) {
  const std::string dir = test::make_temp_dir("materials");
  write_text(dir, "box.mtl",
             "newmtl white\nKd 0.7 0.6 0.5\nKs 0.1 0.2 0.3\nNs 42\n"
             "newmtl light\nKd 0 0 0\nKe 17 12 4\n"
             "newmtl grey1\nKd 0.25\n");
  const std::string path = write_text(dir, "box.obj",
                                      "mtllib box.mtl\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\n"
                                      "usemtl white\nf 1 2 3 4\n"
                                      "usemtl light\nf 1 2 3\nf 1 2 3 4\n"
                                      "f 1 1 5\n"  // zero area: light material but never an emitter
                                      "usemtl grey1\nf 1 3 4\n");
  const LoadedScene loaded = load_obj(path);
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.triangles.size(), 7u);
  ASSERT_EQ(scene.materials.size(), 3u) << "no default material is needed";
  const Material& white = scene.materials[0];
  EXPECT_EQ(white.name, "white");
  EXPECT_EQ(white.kd, Vec3(0.7f, 0.6f, 0.5f));
  EXPECT_EQ(white.ks, Vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(white.ns, 42.0f);
  EXPECT_FALSE(white.emissive());
  EXPECT_TRUE(white.has_specular());
  const Material& light = scene.materials[1];
  EXPECT_EQ(light.ke, Vec3(17.0f, 12.0f, 4.0f));
  EXPECT_TRUE(light.emissive());
  // "Kd 0.25" means grey (tinyobjloader alone would read (0.25, 0, 0)).
  EXPECT_EQ(scene.materials[2].kd, Vec3(0.25f));
  // No Ns: exponent 0 (tinyobjloader alone would read 1).
  EXPECT_EQ(light.ns, 0.0f);
  EXPECT_EQ(scene.materials[2].ns, 0.0f);
  EXPECT_EQ(scene.emitters, (std::vector<uint32_t>{2, 3, 4}));
  EXPECT_EQ(count_with_material(scene, "light"), 4u);
  EXPECT_TRUE(has_warning(loaded, "1 zero-area triangle (kept")) << all_warnings(loaded);
  EXPECT_FALSE(has_warning(loaded, "no emitter")) << all_warnings(loaded);
}

TEST(SceneLoader, TheRayTracedIlluminationModelsMakeMirrorsAndGlass) {
  const std::string dir = test::make_temp_dir("illum");
  write_text(dir, "m.mtl",
             "newmtl plastic\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 20\nNi 1.5\nTf 0.3 0.3 0.3\nillum 2\n"
             "newmtl mirror3\nKs 0.9 0.8 0.7\nillum 3\n"
             "newmtl mirror5\nKd 0.01\nKs 0.95\nNs 1000\nillum 5\n"
             "newmtl glass4\nillum 4\n"  // no Ni: 1.5; no Tf (tinyobjloader: 0): clear
             "newmtl glass6\nNi 1.33\nTf 0.5\nillum 6\n"
             "newmtl glass7\nNi 2.5\nTf 0.1 0.2 0.3\nKs 0.3\nNs 200\nillum 7\n"
             "newmtl highlight8\nKd 0.4\nillum 8\n");
  std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* name : {"plastic", "mirror3", "mirror5", "glass4", "glass6", "glass7", "highlight8"})
    obj += std::string("usemtl ") + name + "\nf 1 2 3\n";
  const LoadedScene loaded = load_obj(write_text(dir, "m.obj", obj));
  const std::vector<Material>& m = loaded.scene.materials;
  ASSERT_GE(m.size(), 7u);  // and the light rig's, as the file has no emitter
  EXPECT_EQ(m[0].surface, SurfaceKind::kBrdf);
  EXPECT_TRUE(m[0].has_specular());
  EXPECT_EQ(m[0].tf, Vec3(1.0f)) << "only glass reads Tf";
  EXPECT_EQ(m[1].surface, SurfaceKind::kMirror);
  EXPECT_EQ(m[1].ks, Vec3(0.9f, 0.8f, 0.7f));
  EXPECT_FALSE(m[1].has_specular()) << "a mirror's Ks is its reflectance, not a Blinn-Phong lobe";
  EXPECT_EQ(m[2].surface, SurfaceKind::kMirror);
  EXPECT_EQ(m[2].kd, Vec3(0.01f));
  EXPECT_EQ(m[3].surface, SurfaceKind::kGlass);
  EXPECT_EQ(m[3].ior, 1.5f);
  EXPECT_EQ(m[3].tf, Vec3(1.0f));
  EXPECT_EQ(m[4].surface, SurfaceKind::kGlass);
  EXPECT_EQ(m[4].ior, 1.33f);
  EXPECT_EQ(m[4].tf, Vec3(0.5f)) << "one Tf value is grey";
  EXPECT_EQ(m[5].surface, SurfaceKind::kGlass);
  EXPECT_EQ(m[5].ior, 2.5f);
  EXPECT_EQ(m[5].tf, Vec3(0.1f, 0.2f, 0.3f));
  EXPECT_FALSE(m[5].has_specular()) << "Ks and Ns do not apply to glass";
  EXPECT_EQ(m[6].surface, SurfaceKind::kBrdf);
  EXPECT_TRUE(all_warnings(loaded).find("illum value") == std::string::npos) << all_warnings(loaded);
}

TEST(SceneLoader, FileNormalsAreUsedAndNormalised) {
  const LoadedScene loaded = load_obj_from_text(kTriangle +
                                                    "vn 0 0 2\nvn 1 0 1\nvn 0 0 0\n"
                                                    "f 1//1 2//2 3//1\n"
                                                    "f 1//1 2//3 3//1\n",  // a zero normal: geometric fallback
                                                "", "normals.obj");
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.triangles.size(), 14u);  // and the light rig's twelve
  EXPECT_EQ(scene.shading_normal(0, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 1.0f));
  const Vec3 at_corner1 = scene.shading_normal(0, 1.0f, 0.0f);
  EXPECT_NEAR(at_corner1.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(at_corner1.z, std::sqrt(0.5f), 1e-6f);
  const Vec3 middle = scene.shading_normal(0, 0.5f, 0.0f);
  EXPECT_NEAR(glm::length(middle), 1.0f, 1e-6f);
  EXPECT_GT(middle.x, 0.0f);
  EXPECT_LT(middle.x, at_corner1.x);
  EXPECT_EQ(scene.triangles[1].n[1], kNoNormal);
  EXPECT_EQ(scene.shading_normal(1, 0.2f, 0.2f), Vec3(0.0f, 0.0f, 1.0f));
}

// ---- warnings ---------------------------------------------------------------------------------------------

TEST(SceneWarnings, MissingMtlUnknownMaterialAndBadValues) {
  const std::string dir = test::make_temp_dir("warnings");
  {
    const std::string path = write_text(dir, "nomtl.obj", "mtllib absent.mtl\n" + kTriangle + "usemtl red\nf 1 2 3\n");
    const LoadedScene loaded = load_obj(path);
    EXPECT_TRUE(has_warning(loaded, "absent.mtl")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "No such file or directory")) << all_warnings(loaded);
    ASSERT_EQ(loaded.scene.triangles.size(), 1u + 12u);  // and the light rig's sky
    EXPECT_EQ(loaded.scene.material_of(0).kd, Vec3(0.5f));
    EXPECT_FALSE(loaded.scene.material_of(0).emissive());
    EXPECT_TRUE(has_warning(loaded, "no emitter: added the default light rig, a sky box"));
  }
  {
    write_text(dir, "mats.mtl",
               "newmtl red\nKd 1 0 0\n"
               "newmtl bad\nKd -0.5 0.5 nan\nKs 0.5 0.5 0.5\nNs -3\nKe 1e999 2 2\n");
    const std::string path = write_text(dir, "mats.obj",
                                        "mtllib mats.mtl\n" + kTriangle +
                                            "f 1 2 3\n"  // before any usemtl
                                            "usemtl red\nf 1 2 3\n"
                                            "usemtl blue\nf 1 2 3\n"
                                            "usemtl bad\nf 1 2 3\n");
    const LoadedScene loaded = load_obj(path);
    const Scene& scene = loaded.scene;
    EXPECT_TRUE(has_warning(loaded, path + ":8: unknown material 'blue'")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "1 triangle before the first usemtl")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "mats.mtl:4: negative Kd value -0.5 clamped to 0")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "mats.mtl:4: Kd value 'nan' is not a finite number")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "mats.mtl:6: negative Ns")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "mats.mtl:7: Ke value '1e999' is not a finite number")) << all_warnings(loaded);
    ASSERT_EQ(scene.triangles.size(), 4u) << "a file emitter means no default light";
    EXPECT_EQ(scene.material_of(0).kd, Vec3(0.5f));
    EXPECT_EQ(scene.material_of(1).name, "red");
    EXPECT_EQ(scene.material_of(2).kd, Vec3(0.5f));
    const Material& bad = scene.material_of(3);
    EXPECT_EQ(bad.name, "bad");
    EXPECT_EQ(bad.kd, Vec3(0.0f, 0.5f, 0.0f));
    EXPECT_EQ(bad.ns, 0.0f);
    EXPECT_EQ(bad.ke, Vec3(0.0f, 2.0f, 2.0f));
    EXPECT_TRUE(bad.emissive());
    EXPECT_EQ(scene.emitters, (std::vector<uint32_t>{3}));
  }
  {
    const LoadedScene loaded = load_obj_from_text(kTriangle + "f 1 2 3\n", "", "plain.obj");
    EXPECT_TRUE(has_warning(loaded, "no materials: using grey diffuse")) << all_warnings(loaded);
  }
}

}  // namespace
}  // namespace lueur
