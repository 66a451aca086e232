// Smooth shading normals as the loader computes them for files without normals: a cube stays sharp, a sphere's
// normals are radial, corners are weighted by angle, and 'off' or a zero crease leaves faces flat.
// Uses the scene layer only (no BVH, no renderer).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"

namespace lueur {
namespace {

using test::cube_obj;
using test::flat_shading;
using test::unit;

// ---- smooth normals ---------------------------------------------------------------------------------------

TEST(SmoothNormals, CubeStaysSharp) {
  for (bool soup : {false, true}) {
    SCOPED_TRACE(soup ? "soup" : "indexed");
    const LoadedScene loaded = load_obj_from_text(cube_obj(soup), "", "cube.obj");
    const Scene& scene = loaded.scene;
    ASSERT_EQ(scene.triangles.size(), 12u + 12u);  // and the light rig's sky
    EXPECT_EQ(scene.normals.size(), 6u) << "identical normals are shared";
    for (uint32_t t = 0; t < 12; ++t) {
      const Vec3 face = unit(scene.geometric_normal_raw(t));
      EXPECT_NEAR(glm::dot(face, Vec3(0.5f) - scene.point(t, 0.3f, 0.3f)), -0.5f, 1e-5f) << "faces point outwards";
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
  EXPECT_GT(n.z, 0.95f);                                  // dominated by the 90-degree corner
  EXPECT_LT(n.z, 0.99999f);                               // but the thin face did contribute
}

}  // namespace
}  // namespace lueur
