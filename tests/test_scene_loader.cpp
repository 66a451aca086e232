// Tests of the scene layer: OBJ/MTL loading and its error messages, normals, the default light, the OBJ writer
// and the shared real-world scenes. Uses the scene layer only (no BVH, no renderer).
#include "scene/obj_loader.h"
#include "scene/obj_writer.h"
#include "scene/scene.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <array>
#include <random>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace lueur {
namespace {

/// Loader options without computed normals: every triangle shaded with its geometric normal.
LoadOptions flat_shading() {
  LoadOptions options;
  options.smooth_normals = false;
  return options;
}

std::string write_text(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

/// Loads `path` expecting a SceneError whose message starts with "path:line: " (line 0: "path: " or any
/// message naming the path) and contains `fragment`.
void expect_error(const std::string& path, size_t line, const std::string& fragment) {
  SCOPED_TRACE(path);
  try {
    load_obj(path);
    ADD_FAILURE() << "no SceneError for " << path;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    if (line > 0) {
      EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ": ", 0), 0u) << message;
    } else {
      EXPECT_NE(message.find(path), std::string::npos) << message;
    }
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

bool has_warning(const LoadedScene& loaded, const std::string& fragment) {
  for (const std::string& w : loaded.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

std::string all_warnings(const LoadedScene& loaded) {
  std::string out;
  for (const std::string& w : loaded.warnings) out += "  " + w + "\n";
  return out;
}

Vec3 unit(const Vec3& v) { return glm::normalize(v); }

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/// Number of triangles whose material is the given one.
size_t count_with_material(const Scene& scene, const std::string& name) {
  size_t n = 0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) n += scene.material_of(t).name == name;
  return n;
}

// ---- basic geometry ---------------------------------------------------------------------------------------

TEST(SceneLoader, QuadBecomesTwoCounterClockwiseTriangles) {
  // Counter-clockwise seen from +Y: both triangles must face +Y and together cover the unit square.
  const LoadedScene loaded =
      load_obj_from_text("v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nf 1 2 3 4\n", "", "quad.obj", flat_shading());
  const Scene& scene = loaded.scene;
  EXPECT_EQ(scene.name, "quad");
  // The default light adds two more triangles above the quad.
  ASSERT_EQ(scene.triangles.size(), 4u);
  float area = 0.0f;
  for (uint32_t t = 0; t < 2; ++t) {
    const Vec3 n = unit(scene.geometric_normal_raw(t));
    EXPECT_NEAR(n.y, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(scene.shading_normal(t, 0.3f, 0.3f), n), 1.0f, 1e-6f);  // no normals: geometric
    area += scene.area(t);
  }
  EXPECT_NEAR(area, 1.0f, 1e-6f);
  const Box3 box = scene.bounds();
  EXPECT_GT(box.hi.y, 0.0f);  // includes the light
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
  EXPECT_EQ(scene.emitters, (std::vector<uint32_t>{2, 3, 4}));
  EXPECT_EQ(count_with_material(scene, "light"), 4u);
  EXPECT_TRUE(has_warning(loaded, "1 zero-area triangle (kept")) << all_warnings(loaded);
  EXPECT_FALSE(has_warning(loaded, "no emitter")) << all_warnings(loaded);
}

TEST(SceneLoader, FileNormalsAreUsedAndNormalised) {
  const LoadedScene loaded = load_obj_from_text(kTriangle +
                                                    "vn 0 0 2\nvn 1 0 1\nvn 0 0 0\n"
                                                    "f 1//1 2//2 3//1\n"
                                                    "f 1//1 2//3 3//1\n",  // a zero normal: geometric fallback
                                                "", "normals.obj");
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.triangles.size(), 4u);
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

// ---- smooth normals ---------------------------------------------------------------------------------------

std::string cube_obj(bool soup) {
  const char* corners = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
  std::ostringstream obj;
  if (!soup) obj << corners;
  for (int f = 0; f < 6; ++f) {
    if (soup) {
      // Every face gets its own copies of its corners, as exporters of triangle soups write them.
      static const float p[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      for (int k = 0; k < 4; ++k) {
        const float* q = p[faces[f][k] - 1];
        obj << "v " << q[0] << " " << q[1] << " " << q[2] << "\n";
      }
      obj << "f -4 -3 -2 -1\n";
    } else {
      obj << "f " << faces[f][0] << " " << faces[f][1] << " " << faces[f][2] << " " << faces[f][3] << "\n";
    }
  }
  return obj.str();
}

TEST(SmoothNormals, CubeStaysSharp) {
  for (bool soup : {false, true}) {
    SCOPED_TRACE(soup ? "soup" : "indexed");
    const LoadedScene loaded = load_obj_from_text(cube_obj(soup), "", "cube.obj");
    const Scene& scene = loaded.scene;
    ASSERT_EQ(scene.triangles.size(), 12u + 2u);
    EXPECT_EQ(scene.normals.size(), 6u) << "identical normals are shared";
    for (uint32_t t = 0; t < 12; ++t) {
      const Vec3 face = unit(scene.geometric_normal_raw(t));
      EXPECT_NEAR(glm::dot(face, Vec3(0.5f) - scene.point(t, 0.3f, 0.3f)), -0.5f, 1e-5f)
          << "faces point outwards";
      for (uint32_t c = 0; c < 3; ++c) {
        ASSERT_NE(scene.triangles[t].n[c], kNoNormal);
        const Vec3 n = scene.normals[scene.triangles[t].n[c]];
        EXPECT_NEAR(glm::dot(n, face), 1.0f, 1e-6f) << "triangle " << t << " corner " << c;
      }
    }
  }
}

std::string sphere_obj(int rings, int segments, bool soup) {
  std::vector<Vec3> p;
  for (int r = 0; r <= rings; ++r) {
    const float theta = kPi * static_cast<float>(r) / static_cast<float>(rings);
    for (int s = 0; s < segments; ++s) {
      const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
      // The poles are exact: sin(pi) in float is not 0, and near-coincident points would make slivers.
      if (r == 0 || r == rings) {
        p.emplace_back(0.0f, r == 0 ? 1.0f : -1.0f, 0.0f);
      } else {
        p.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      }
    }
  }
  auto id = [&](int r, int s) { return r * segments + (s % segments); };
  std::vector<std::array<int, 3>> tris;
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      // Outward winding; the pole rows collapse to zero-area triangles, which must not disturb the result.
      tris.push_back({id(r, s), id(r, s + 1), id(r + 1, s)});
      tris.push_back({id(r, s + 1), id(r + 1, s + 1), id(r + 1, s)});
    }
  }
  std::ostringstream obj;
  obj.precision(9);
  if (!soup) {
    for (const Vec3& q : p) obj << "v " << q.x << " " << q.y << " " << q.z << "\n";
    for (const auto& t : tris) obj << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  } else {
    for (const auto& t : tris) {
      for (int k : t) obj << "v " << p[k].x << " " << p[k].y << " " << p[k].z << "\n";
      obj << "f -3 -2 -1\n";
    }
  }
  return obj.str();
}

TEST(SmoothNormals, LowPolySphereNormalsAreRadial) {
  for (bool soup : {false, true}) {
    SCOPED_TRACE(soup ? "soup" : "indexed");
    const LoadedScene loaded = load_obj_from_text(sphere_obj(8, 12, soup), "", "sphere.obj");
    const Scene& scene = loaded.scene;
    size_t checked = 0;
    float worst = 1.0f;
    for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
      if (scene.material_of(t).emissive()) continue;
      for (uint32_t c = 0; c < 3; ++c) {
        const Vec3 radial = unit(scene.positions[scene.triangles[t].v[c]]);
        if (!(scene.area(t) > 0.0f)) {
          EXPECT_EQ(scene.triangles[t].n[c], kNoNormal);
          continue;
        }
        ASSERT_NE(scene.triangles[t].n[c], kNoNormal);
        worst = std::min(worst, glm::dot(scene.normals[scene.triangles[t].n[c]], radial));
        ++checked;
      }
      // Interpolated shading normals are close to radial inside the triangle too, far closer than the face's.
      const Vec3 inside = unit(scene.point(t, 0.3f, 0.3f));
      if (scene.area(t) > 0.0f) {
        EXPECT_GT(glm::dot(scene.shading_normal(t, 0.3f, 0.3f), inside), 0.995f);
      }
    }
    EXPECT_GT(checked, 400u);
    EXPECT_GT(worst, 0.99f);
  }
}

TEST(SmoothNormals, OffKeepsGeometricNormalsAndCreaseZeroIsFlat) {
  const LoadedScene flat = load_obj_from_text(sphere_obj(8, 12, false), "", "sphere.obj", flat_shading());
  EXPECT_TRUE(flat.scene.normals.empty());
  for (const Triangle& t : flat.scene.triangles) EXPECT_EQ(t.n[0], kNoNormal);

  Scene scene = load_obj_from_text(sphere_obj(8, 12, false), "", "sphere.obj").scene;
  compute_smooth_normals(scene, 0.0f);
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    if (!(scene.area(t) > 0.0f) || scene.material_of(t).emissive()) continue;
    EXPECT_NEAR(glm::dot(scene.shading_normal(t, 0.2f, 0.3f), unit(scene.geometric_normal_raw(t))), 1.0f, 1e-5f);
  }
  clear_normals(scene);
  EXPECT_TRUE(scene.normals.empty());
}

TEST(SmoothNormals, WeightsByCornerAngle) {
  // A vertex shared by one big triangle in the XY plane (90 degree corner) and two thin ones tilted 45 degrees
  // (small corners): angle weighting keeps the result near the big face's normal; crease 60 lets all join.
  Scene scene;
  scene.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0.1f, 1), Vec3(-1, -0.1f, 1)};
  scene.materials.push_back(Material{});
  Triangle big;
  big.v[1] = 1;
  big.v[2] = 2;
  Triangle thin;
  thin.v[1] = 3;
  thin.v[2] = 4;
  scene.triangles = {big, thin};
  compute_smooth_normals(scene, 60.0f);
  const Vec3 n = scene.normals[scene.triangles[0].n[0]];
  const Vec3 thin_normal = unit(scene.geometric_normal_raw(1));
  EXPECT_GT(glm::dot(thin_normal, Vec3(0, 0, 1)), 0.5f);  // within the crease
  EXPECT_GT(n.z, 0.95f);                                   // dominated by the 90-degree corner
  EXPECT_LT(n.z, 0.99999f);                                // but the thin face did contribute
}

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

// ---- bad input --------------------------------------------------------------------------------------------

TEST(SceneErrors, MissingFileAndDirectory) {
  const std::string dir = test::make_temp_dir("errors-files");
  expect_error(dir + "/nothing-here.obj", 0, "cannot open '" + dir + "/nothing-here.obj': No such file or directory");
  expect_error(dir, 0, "cannot open '" + dir + "': Is a directory");
  expect_error(write_text(dir, "empty.obj", ""), 0, "empty.obj: no triangles");
  expect_error(write_text(dir, "points.obj", "# only points\nv 0 0 0\nv 1 0 0\np 1 2\nl 1 2\n"), 0,
               "points.obj: no triangles");
  if (::geteuid() != 0) {  // root reads anything
    const std::string locked = write_text(dir, "locked.obj", kTriangle + "f 1 2 3\n");
    ::chmod(locked.c_str(), 0);
    expect_error(locked, 0, "Permission denied");
  }
}

TEST(SceneErrors, EachBadLineNamesFileAndLine) {
  const std::string dir = test::make_temp_dir("errors-lines");
  struct Case {
    const char* file;
    std::string text;
    size_t line;
    const char* fragment;
  };
  const std::string t = kTriangle;  // lines 1-3
  const Case cases[] = {
      {"garbage.obj", t + "f 1 2 3\nhello world\n", 5, "unknown statement 'hello'"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'nan' is not a finite number"},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", 3, "'-inf' is not a finite number"},
      {"huge.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'1e39' is not a finite number"},
      {"junk-number.obj", "v 0 0 0\nv 1.5abc 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'1.5abc' is not a number"},
      {"short-vertex.obj", "v 0 0\n", 1, "vertex needs three coordinates"},
      {"out-of-range.obj", t + "\n# comment\nf 1 2 40\n", 6,
       "face index 40 out of range (file has 3 vertices so far)"},
      {"negative-out-of-range.obj", t + "f -1 -2 -4\n", 4, "face index -4 out of range"},
      {"forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", 3, "face index 3 out of range"},
      {"normal-range.obj", t + "vn 0 0 1\nf 1//1 2//2 3//1\n", 5, "face normal index 2 out of range"},
      {"texture-range.obj", t + "f 1/1 2/1 3/1\n", 4, "face texture index 1 out of range"},
      {"two-vertices.obj", t + "f 1 2\n", 4, "face has 2 vertices (needs at least 3)"},
      {"index-zero.obj", t + "f 0 1 2\n", 4, "face index 0"},
      {"not-integer.obj", t + "f 1 2 x\n", 4, "not an integer index"},
      {"float-index.obj", t + "f 1 2 3.5\n", 4, "not an integer index"},
      {"binary.obj", t + "f 1 2 3\n\x7f" + "ELF" + std::string("\x02\x01\x01\0\0\0", 6) + "garbage", 5,
       "binary data (byte 0x7f)"},
      {"nul.obj", t + std::string("f 1 2 3\0\n", 9), 4, "binary data (byte 0x00)"},
      {"crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 9\r\n", 4, "face index 9 out of range"},
      {"lone-cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 9\r", 4, "face index 9 out of range"},
  };
  for (const Case& c : cases) expect_error(write_text(dir, c.file, c.text), c.line, c.fragment);

  // Pure binary garbage from the start.
  std::string noise(4096, '\0');
  std::mt19937 rng(7);
  for (char& ch : noise) ch = static_cast<char>(rng() & 0xff);
  expect_error(write_text(dir, "noise.obj", noise), 1, "binary data");
}

TEST(SceneErrors, CommittedSamples) {
  const std::string bad = std::string(LUEUR_TEST_SCENES) + "/bad/";
  expect_error(bad + "garbage_line.obj", 5, "unknown statement");
  expect_error(bad + "index_out_of_range.obj", 7, "face index 12 out of range (file has 4 vertices so far)");
  expect_error(bad + "nan_vertex.obj", 3, "is not a finite number");
}

TEST(SceneErrors, InMemoryTextUsesTheGivenName) {
  try {
    load_obj_from_text(kTriangle + "f 1 2 3 4\n", "", "memory.obj");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "memory.obj:4: face index 4 out of range (file has 3 vertices so far)");
  }
}

// ---- warnings ---------------------------------------------------------------------------------------------

TEST(SceneWarnings, MissingMtlUnknownMaterialAndBadValues) {
  const std::string dir = test::make_temp_dir("warnings");
  {
    const std::string path = write_text(dir, "nomtl.obj", "mtllib absent.mtl\n" + kTriangle + "usemtl red\nf 1 2 3\n");
    const LoadedScene loaded = load_obj(path);
    EXPECT_TRUE(has_warning(loaded, "absent.mtl")) << all_warnings(loaded);
    EXPECT_TRUE(has_warning(loaded, "No such file or directory")) << all_warnings(loaded);
    ASSERT_EQ(loaded.scene.triangles.size(), 3u);
    EXPECT_EQ(loaded.scene.material_of(0).kd, Vec3(0.5f));
    EXPECT_FALSE(loaded.scene.material_of(0).emissive());
    EXPECT_TRUE(has_warning(loaded, "no emitter: added a default area light above the scene"));
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

// ---- size limits ------------------------------------------------------------------------------------------

TEST(SceneLimits, MegabyteLines) {
  std::string comment = "# " + std::string(1 << 20, 'x') + "\n";
  // A valid triangle face one megabyte long: indices with many leading zeros.
  const std::string zeros(350000, '0');
  std::string face = "f " + zeros + "1 " + zeros + "2 " + zeros + "3\n";
  ASSERT_GT(face.size(), 1000000u);
  const LoadedScene loaded = load_obj_from_text(comment + kTriangle + face + comment, "", "long.obj");
  ASSERT_EQ(loaded.scene.triangles.size(), 3u);
  EXPECT_EQ(loaded.scene.triangles[0].v[2], 2u);

  // One megabyte of blanks between tokens is fine too.
  const std::string spaced = kTriangle + "f 1" + std::string(1 << 20, ' ') + "2\t3\n";
  EXPECT_EQ(load_obj_from_text(spaced, "", "spaced.obj").scene.triangles.size(), 3u);
}

TEST(SceneLimits, FaceWithFiveThousandVertices) {
  const int n = 5000;
  std::ostringstream obj;
  obj.precision(9);
  for (int i = 0; i < n; ++i) {
    // A star-shaped (concave) polygon in the XY plane, counter-clockwise from +Z.
    const float a = 2.0f * kPi * static_cast<float>(i) / n;
    const float r = (i % 2) ? 0.8f : 1.0f;
    obj << "v " << r * std::cos(a) << " " << r * std::sin(a) << " 0\n";
  }
  obj << "f";
  for (int i = 1; i <= n; ++i) obj << " " << i;
  obj << "\n";
  const auto start = std::chrono::steady_clock::now();
  const LoadedScene loaded = load_obj_from_text(obj.str(), "", "polygon.obj");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 10.0);
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.triangles.size(), static_cast<size_t>(n - 2) + 2u);
  double area = 0.0;
  for (uint32_t t = 0; t < static_cast<uint32_t>(n - 2); ++t) {
    const Vec3 g = scene.geometric_normal_raw(t);
    EXPECT_GE(g.z, 0.0f) << "triangle " << t << " flipped";
    area += 0.5 * g.z;
  }
  // Area of the star: n/2 kites, each two triangles (1, 0.8) around the centre.
  const double expected = n * 0.5 * 1.0 * 0.8 * std::sin(2.0 * M_PI / n);
  EXPECT_NEAR(area, expected, 1e-3 * expected);
}

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
      {"stanford-bunny/stanford-bunny.obj", 69451 + 2, 2, true},
      {"conference/conference.obj", 331179 + 2, 2, true},
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
      for (uint32_t e : scene.emitters) EXPECT_EQ(scene.material_of(e).name, "lueur-default-light");
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
