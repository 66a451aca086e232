// The single overhead light the benchmarks add to scenes without emitters (add_default_light; the loader adds the
// light rig instead, tested in test_light_rig.cpp): where it is, which way it faces, and the irradiance
// it gives, compared with the exact value from Lambert's polygon formula (test::lambert_irradiance, whose own checks
// are here too: a closed form, two limits and a brute-force quadrature). Uses the scene layer only.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "scene/scene.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::lambert_irradiance;
using test::unit;

// ---- Lambert's formula (test::lambert_irradiance) -------------------------------------------------------

/// Irradiance at p (normal n) from triangle `tri` (counter-clockwise seen from its emitting side) of radiance `le`,
/// by the centroid rule on the regular split of the triangle into cells^2 sub-triangles: a brute-force integral
/// that shares nothing with Lambert's formula. Its error falls as 1 / cells^2.
double quadrature_irradiance(const std::array<glm::dvec3, 3>& tri, const glm::dvec3& p, const glm::dvec3& n, double le,
                             int cells) {
  const glm::dvec3 e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
  const glm::dvec3 light_normal = glm::normalize(glm::cross(e1, e2));
  const double cell_area = 0.5 * glm::length(glm::cross(e1, e2)) / (static_cast<double>(cells) * cells);
  double sum = 0.0;
  for (int i = 0; i < cells; ++i) {
    for (int j = 0; j < cells - i; ++j) {
      // An upright sub-triangle at every (i, j) and an inverted one beside it, except along the diagonal.
      for (int flip = 0; flip < (j < cells - i - 1 ? 2 : 1); ++flip) {
        const double u = (i + (flip ? 2.0 : 1.0) / 3.0) / cells, v = (j + (flip ? 2.0 : 1.0) / 3.0) / cells;
        const glm::dvec3 d = tri[0] + u * e1 + v * e2 - p;
        const double r2 = glm::dot(d, d), r = std::sqrt(r2);
        const double cos_receiver = std::max(0.0, glm::dot(n, d) / r);
        const double cos_light = std::max(0.0, -glm::dot(light_normal, d) / r);
        sum += le * cos_receiver * cos_light / r2 * cell_area;
      }
    }
  }
  return sum;
}

/// A centred, downward-facing rectangle (half-sides a along x, b along z) at height h above the origin, its corners
/// counter-clockwise seen from below.
std::vector<glm::dvec3> rectangle_above_origin(double a, double b, double h) {
  return {{-a, h, -b}, {a, h, -b}, {a, h, b}, {-a, h, b}};
}

TEST(LambertFormula, MatchesTheClosedFormOfARectangleCentredAbove) {
  // The textbook closed form for a point on the axis of a parallel rectangle, with c = sqrt(a^2 + h^2) and
  // d = sqrt(b^2 + h^2): E = 2 le (a / c atan(b / c) + b / d atan(a / d)). It is Lambert's sum worked out by
  // hand, with no cross products or winding: this checks the helper's vector code, to double precision.
  const double a = 0.7, b = 0.4, h = 1.3, le = 3.0;
  const double c = std::sqrt(a * a + h * h), d = std::sqrt(b * b + h * h);
  const double closed_form = 2.0 * le * (a / c * std::atan(b / c) + b / d * std::atan(a / d));
  const double e = lambert_irradiance(rectangle_above_origin(a, b, h), glm::dvec3(0.0), glm::dvec3(0, 1, 0), le);
  EXPECT_NEAR(e, closed_form, 1e-12 * closed_form);
}

TEST(LambertFormula, SmallFarSquareIsAreaTimesCosinesOverDistanceSquared) {
  // A square of side s = 0.01 at distance 100, seen 30 degrees off the receiver's normal and tilted 40 degrees from
  // facing it. The point-light form le A cos cos / d^2 differs from the exact value by order (s / d)^2 = 1e-8
  // (measured: 1.5e-9); 1e-7 leaves a margin without admitting a wrong factor or cosine.
  const double pi = 3.14159265358979323846, alpha = pi / 6.0, beta = 2.0 * pi / 9.0, distance = 100.0;
  const double half = 0.005, le = 2.0;
  const glm::dvec3 n(0, 1, 0);
  const glm::dvec3 toward(std::sin(alpha), std::cos(alpha), 0.0);  // from the receiver to the square's centre
  const glm::dvec3 centre = distance * toward;
  // The light's normal: -toward turned by beta about z, then the square's axes u, v with u x v = light_normal.
  const glm::dvec3 light_normal(-std::sin(alpha + beta), -std::cos(alpha + beta), 0.0);
  const glm::dvec3 u(0, 0, 1), v = glm::cross(light_normal, u);
  const std::vector<glm::dvec3> square = {centre - half * u - half * v, centre + half * u - half * v,
                                          centre + half * u + half * v, centre - half * u + half * v};
  const double point_light = le * (4.0 * half * half) * std::cos(alpha) * std::cos(beta) / (distance * distance);
  EXPECT_NEAR(lambert_irradiance(square, glm::dvec3(0.0), n, le), point_light, 1e-7 * point_light);
}

TEST(LambertFormula, PointUnderAHugeSquareGetsPiLe) {
  // A square of half-side a = 1e4 at height h = 1 misses the hemisphere's cosine-weighted share
  // (1/2 + 1/pi) (h / a)^2 = 8.2e-9 (from the closed form 4 s atan(s) / pi, s = a / sqrt(a^2 + h^2)), below 1e-8.
  const double le = 1.5;
  const double e = lambert_irradiance(rectangle_above_origin(1e4, 1e4, 1.0), glm::dvec3(0.0), glm::dvec3(0, 1, 0), le);
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(e, pi * le, 1e-8 * pi * le);
}

TEST(LambertFormula, AgreesWithQuadratureOverAnObliqueTriangle) {
  // A large triangle seen from close by, under a tilted receiver: every cosine and distance varies across it.
  const std::array<glm::dvec3, 3> tri = {glm::dvec3(-0.5, 1.2, -0.4), glm::dvec3(0.9, 1.5, 0.1),
                                         glm::dvec3(0.1, 1.0, 0.8)};
  const glm::dvec3 p(0.2, -0.1, 0.3), n = glm::normalize(glm::dvec3(0.3, 1.0, -0.2));
  const double le = 2.5;
  const double exact = lambert_irradiance({tri[0], tri[1], tri[2]}, p, n, le);
  const double coarse = quadrature_irradiance(tri, p, n, le, 100), fine = quadrature_irradiance(tri, p, n, le, 200);
  // The centroid rule's error falls as 1 / cells^2, so the fine estimate is off by about |coarse - fine| / 3
  // (Richardson); allowing the whole difference leaves a factor 3. The difference itself must be small, or the
  // check would be loose.
  EXPECT_LT(std::fabs(coarse - fine), 1e-4 * exact);
  EXPECT_NEAR(fine, exact, std::fabs(coarse - fine));
}

TEST(LambertFormula, BackSideGivesZeroAndBelowTheHorizonGivesNaN) {
  const std::vector<glm::dvec3> light = rectangle_above_origin(0.5, 0.5, 1.0);  // faces down
  EXPECT_GT(lambert_irradiance(light, glm::dvec3(0.0), glm::dvec3(0, 1, 0), 1.0), 0.0);
  EXPECT_EQ(lambert_irradiance(light, glm::dvec3(0, 2, 0), glm::dvec3(0, -1, 0), 1.0), 0.0);  // sees the back
  // Tilted until two corners sink below the receiver's horizon: the formula would count them negatively.
  EXPECT_TRUE(std::isnan(lambert_irradiance(light, glm::dvec3(0.0), glm::normalize(glm::dvec3(1, 0.1, 0)), 1.0)));
}

// ---- the default light ------------------------------------------------------------------------------------

/// Irradiance at `at` (normal n) from the scene's emitters as built: Lambert's formula on each emitting triangle's
/// float corners, with its Ke (the default light is grey, so the red channel stands for all three).
double emitted_irradiance(const Scene& scene, const Vec3& at, const Vec3& n) {
  double e = 0.0;
  for (uint32_t t : scene.emitters) {
    const Triangle& tri = scene.triangles[t];
    const std::vector<glm::dvec3> corners = {glm::dvec3(scene.positions[tri.v[0]]),
                                             glm::dvec3(scene.positions[tri.v[1]]),
                                             glm::dvec3(scene.positions[tri.v[2]])};
    e += lambert_irradiance(corners, glm::dvec3(at), glm::dvec3(n), scene.material_of(t).ke.r);
  }
  return e;
}

/// The default light as add_default_light describes it, in double: a square of side size / 2 centred over the box
/// at height hi.y + size / 2, facing down, with radiance pi d^2 / A, where d is its height above the box centre
/// and A its area, so that a point light of the same power would give E = pi at the centre.
struct DesignedLight {
  std::vector<glm::dvec3> corners;
  double le = 0.0;
};

DesignedLight designed_light(const Box3& box, double size) {
  const glm::dvec3 lo(box.lo), hi(box.hi), centre = 0.5 * (lo + hi);
  const double half = 0.25 * size, height = hi.y + 0.5 * size, d = 0.5 * (hi.y - lo.y) + 0.5 * size;
  DesignedLight light;
  light.corners = {{centre.x - half, height, centre.z - half},
                   {centre.x + half, height, centre.z - half},
                   {centre.x + half, height, centre.z + half},
                   {centre.x - half, height, centre.z + half}};
  light.le = 3.14159265358979323846 * d * d / (4.0 * half * half);
  return light;
}

/// What the designed light gives at the box centre, by Lambert's formula in double.
double designed_irradiance(const Box3& box, double size) {
  const DesignedLight light = designed_light(box, size);
  return lambert_irradiance(light.corners, glm::dvec3(box.center()), glm::dvec3(0, 1, 0), light.le);
}

/// The scene's light is the designed one rounded to float. Each corner coordinate moves by up to 2^-24 (6e-8) of its
/// magnitude, here at most 21 half-sides of the light (the zero-size box at (3, 4, 5), half-side 0.25), so the
/// light's sides and height change by at most about 2e-6 of themselves. E depends on their ratios at most
/// quadratically: it moves by a few 1e-6 at most, plus Le's own rounding (6e-8); 1e-5 bounds that (measured: 3e-8
/// to 1e-7). A light 0.1% off in size, height or radiance fails by a factor of 100.
constexpr double kFloatTolerance = 1e-5;

TEST(DefaultLight, FacesDownAboveTheSceneWithTheDesignedIrradiance) {
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
  // The light is half as wide as it is far: the cosines cost about 8 percent against the point estimate (0.923 pi).
  const double expected = designed_irradiance(box, glm::length(glm::dvec3(box.hi) - glm::dvec3(box.lo)));
  EXPECT_NEAR(emitted_irradiance(scene, box.center(), Vec3(0, 1, 0)), expected, kFloatTolerance * expected);
}

TEST(DefaultLight, FlatSceneGetsLambertsExactIrradiance) {
  LoadOptions no_rig;
  no_rig.light_rig = false;
  Scene scene =
      load_obj_from_text("v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nf 1 2 3 4\n", "", "floor.obj", no_rig).scene;
  add_default_light(scene);
  ASSERT_EQ(scene.emitters.size(), 2u);
  // The floor's box is 2 x 0 x 2, its diagonal 2 sqrt 2: the default light is a square of half-side a = sqrt 2 / 2
  // at height h = sqrt 2, with Le = pi h^2 / (2a)^2 = pi. As wide as it is high, its cosines take their share:
  // E = 4 Le s atan(s) with s = a / sqrt(a^2 + h^2) = 1 / sqrt 5, about 0.752 pi.
  const double s = 1.0 / std::sqrt(5.0), pi = 3.14159265358979323846;
  Box3 floor;
  floor.expand(Vec3(-1, 0, -1));
  floor.expand(Vec3(1, 0, 1));
  const double expected = designed_irradiance(floor, 2.0 * std::sqrt(2.0));
  EXPECT_NEAR(expected, 4.0 * pi * s * std::atan(s), 1e-12);
  EXPECT_NEAR(emitted_irradiance(scene, Vec3(0.0f), Vec3(0, 1, 0)), expected, kFloatTolerance * expected);
}

TEST(DefaultLight, ZeroSizeSceneStillGetsAFiniteLight) {
  Scene scene;
  scene.positions = {Vec3(3, 4, 5)};
  scene.materials.push_back(Material{});
  scene.triangles.push_back(Triangle{});  // all three corners on the one point
  const Box3 box = scene.bounds();
  add_default_light(scene);
  ASSERT_EQ(scene.emitters.size(), 2u);
  const Material& light = scene.material_of(scene.emitters[0]);
  EXPECT_TRUE(std::isfinite(light.ke.r));
  EXPECT_GT(light.ke.r, 0.0f);
  EXPECT_NEAR(scene.area(1) + scene.area(2), 0.25f, 1e-5f);
  // A box without size gets a unit size: a square of side 0.5 at height 0.5, as wide as high (0.752 pi).
  const double expected = designed_irradiance(box, 1.0);
  EXPECT_NEAR(emitted_irradiance(scene, Vec3(3, 4, 5), Vec3(0, 1, 0)), expected, kFloatTolerance * expected);

  Scene empty;
  add_default_light(empty);
  EXPECT_EQ(empty.emitters.size(), 2u);
  EXPECT_TRUE(is_finite(empty.positions[0]));
}

}  // namespace
}  // namespace lueur
