// Smooth shading normals as the loader computes them for files without normals: a cube stays sharp, a sphere's
// normals are radial, corners are weighted by angle, and 'off' or a zero crease leaves faces flat.
// Uses the scene layer only (no BVH, no renderer).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
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

// A terrain of a few tens of thousands of vertices, large enough that the pass splits it in ranges: smooth hills,
// a sawtooth ridge whose faces meet beyond the crease, flat terraces (one normal shared far and wide), triangle-
// soup copies of some corners (welded by position) and a few zero-area triangles.
Scene terrain_scene() {
  constexpr int kSide = 160;
  Scene scene;
  scene.materials.push_back(Material{});
  const auto height = [](int x, int z) {
    if (z < 40) return 0.25f * std::floor(static_cast<float>(x) / 16.0f);                             // terraces
    if (z < 60) return (x % 2 == 0) ? 0.0f : 3.0f;                                                    // sawtooth ridge
    return 0.4f * std::sin(0.21f * static_cast<float>(x)) * std::cos(0.17f * static_cast<float>(z));  // hills
  };
  for (int z = 0; z < kSide; ++z)
    for (int x = 0; x < kSide; ++x)
      scene.positions.emplace_back(static_cast<float>(x), height(x, z), static_cast<float>(z));
  const auto id = [&](int x, int z) { return static_cast<uint32_t>(z * kSide + x); };
  for (int z = 0; z + 1 < kSide; ++z)
    for (int x = 0; x + 1 < kSide; ++x) {
      Triangle a, b;
      a.v[0] = id(x, z), a.v[1] = id(x, z + 1), a.v[2] = id(x + 1, z);
      b.v[0] = id(x + 1, z), b.v[1] = id(x, z + 1), b.v[2] = id(x + 1, z + 1);
      if ((x * 7 + z * 3) % 11 == 0) {  // a soup: this triangle's own copies of its corners
        for (uint32_t& v : b.v) {
          scene.positions.push_back(scene.positions[v]);
          v = static_cast<uint32_t>(scene.positions.size() - 1);
        }
      }
      scene.triangles.push_back(a);
      scene.triangles.push_back(b);
      if ((x + z) % 97 == 0) {  // zero area: no part in any blend
        Triangle flat;
        flat.v[0] = flat.v[1] = id(x, z), flat.v[2] = id(x + 1, z);
        scene.triangles.push_back(flat);
      }
    }
  return scene;
}

TEST(SmoothNormals, MatchBruteForceAndTheSameBytesOnAnyThreadCount) {
  const Scene input = terrain_scene();
  Scene one = input;
  compute_smooth_normals(one, 60.0f, 1);

  // Brute force: every corner blends, weighted by corner angle, the unit normals of all faces at a position equal
  // to its own whose normal lies within the crease of its face's.
  const auto face_normal = [&](uint32_t t) { return unit(input.geometric_normal_raw(t)); };
  const auto angle = [&](uint32_t t, uint32_t c) {
    const Triangle& tri = input.triangles[t];
    const Vec3 at = input.positions[tri.v[c]];
    const Vec3 e1 = input.positions[tri.v[(c + 1) % 3]] - at, e2 = input.positions[tri.v[(c + 2) % 3]] - at;
    return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
  };
  std::map<std::array<float, 3>, std::vector<std::pair<uint32_t, uint32_t>>> at_position;
  for (uint32_t t = 0; t < input.triangles.size(); ++t) {
    if (!(glm::length(input.geometric_normal_raw(t)) > 0.0f)) continue;
    for (uint32_t c = 0; c < 3; ++c) {
      const Vec3 p = input.positions[input.triangles[t].v[c]];
      at_position[{p.x, p.y, p.z}].emplace_back(t, c);
    }
  }
  const float cos_crease = std::cos(60.0f * kPi / 180.0f) - 1e-6f;
  size_t checked = 0, sharp = 0;
  for (const auto& [position, corners] : at_position) {
    for (const auto& [t, c] : corners) {
      Vec3 sum(0.0f);
      bool beyond_crease = false;
      for (const auto& [other, other_corner] : corners) {
        if (glm::dot(face_normal(t), face_normal(other)) >= cos_crease) {
          sum += angle(other, other_corner) * face_normal(other);
        } else {
          beyond_crease = true;
        }
      }
      const Vec3 expected = unit(sum);
      ASSERT_NE(one.triangles[t].n[c], kNoNormal);
      const Vec3 got = one.normals[one.triangles[t].n[c]];
      ASSERT_NEAR(glm::dot(got, expected), 1.0f, 2e-6f) << "triangle " << t << " corner " << c;
      sharp += beyond_crease;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100000u);
  EXPECT_GT(sharp, 1000u) << "corners with faces beyond the crease (the ridge's) are covered";
  for (uint32_t t = 0; t < input.triangles.size(); ++t)
    if (!(glm::length(input.geometric_normal_raw(t)) > 0.0f)) {
      EXPECT_EQ(one.triangles[t].n[0], kNoNormal);
    }
  // Equal normals share one entry: the terraces' flat faces are one normal each, not thousands.
  std::set<std::array<float, 3>> distinct;
  for (const Vec3& n : one.normals) distinct.insert({n.x + 0.0f, n.y + 0.0f, n.z + 0.0f});
  EXPECT_EQ(distinct.size(), one.normals.size());
  EXPECT_LT(one.normals.size(), input.positions.size());

  for (unsigned threads : {2u, 3u, 5u, 8u}) {
    SCOPED_TRACE(threads);
    Scene many = input;
    compute_smooth_normals(many, 60.0f, threads);
    ASSERT_EQ(many.normals.size(), one.normals.size());
    EXPECT_EQ(std::memcmp(many.normals.data(), one.normals.data(), one.normals.size() * sizeof(Vec3)), 0);
    for (size_t t = 0; t < one.triangles.size(); ++t)
      for (uint32_t c = 0; c < 3; ++c) ASSERT_EQ(many.triangles[t].n[c], one.triangles[t].n[c]) << t;
  }
}

}  // namespace
}  // namespace lueur
