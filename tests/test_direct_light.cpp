// L1 against closed forms: the emitting closed box (L1 = rho Le at every pixel, every strategy) and the irradiance
// of a rectangular light from Lambert's polygon formula. Tolerances come from the estimator's own standard error.
#include <gtest/gtest.h>

#include <array>
#include <optional>

#include "core/rng.h"
#include "integrator/brdf.h"
#include "integrator/camera_light.h"
#include "integrator/direct_light.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "test_support.h"

namespace lueur {
namespace {

struct Estimate {
  Vec3 mean{0.0f};
  Vec3 standard_error{0.0f};
};

/// Mean and standard error of `n` independent one-sample L1 estimates at a surface point.
Estimate estimate_with_error(const TracedScene& traced, const SurfacePoint& sp, DirectLightOptions options, int n,
                             uint64_t seed) {
  options.rays = 1;
  PixelSampler sampler(SamplerKind::kIndependent, seed, 17, 0, RngPurpose::kDirect);  // independent samples
  uint64_t rays = 0;
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 x(estimate_direct_light(traced, sp, options, sampler, static_cast<uint64_t>(i), rays));
    sum += x;
    sum2 += x * x;
  }
  const glm::dvec3 mean = sum / static_cast<double>(n);
  const glm::dvec3 variance = glm::max(sum2 / static_cast<double>(n) - mean * mean, glm::dvec3(0.0));
  return {Vec3(mean), Vec3(glm::sqrt(variance / static_cast<double>(n - 1)))};
}

/// Five standard errors plus a float-rounding floor: a real bias of that size fails.
void expect_within_error(const Estimate& e, const Vec3& expected, const std::string& where) {
  for (int c = 0; c < 3; ++c) {
    const float tolerance = 5.0f * e.standard_error[c] + 1e-4f * std::fabs(expected[c]);
    EXPECT_NEAR(e.mean[c], expected[c], tolerance) << where << " channel " << c;
  }
}

class ClosedBox : public ::testing::TestWithParam<LightStrategy> {};

TEST_P(ClosedBox, DirectLightIsRhoTimesLeAtEveryPixel) {
  const Vec3 rho(0.5f, 0.7f, 0.3f), le(2.0f, 1.0f, 4.0f);
  const auto traced = prepare_scene(test::make_closed_emitting_box(1.0f, rho, le));
  // Every geometric normal points into the box.
  for (uint32_t t = 0; t < traced->scene.triangles.size(); ++t) {
    const Vec3 c = (traced->scene.point(t, 1.0f / 3, 1.0f / 3));
    EXPECT_LT(glm::dot(traced->scene.geometric_normal_raw(t), c), 0.0f);
  }
  DirectLightOptions options;
  options.strategy = GetParam();
  options.blinn_k = 1.0f;
  // 12 x 12 images of the floor and of two walls, seen from the centre (the edges and corners have a test of their
  // own, below).
  const Vec3 expected = rho * le;
  const CameraSpec views[] = {{Vec3(0.0f), Vec3(0, -1, 0), Vec3(0, 0, -1), 60.0f},
                              {Vec3(0.0f), Vec3(-1, 0, 0), Vec3(0, 1, 0), 60.0f},
                              {Vec3(0.0f), Vec3(0, 0, 1), Vec3(0, 1, 0), 60.0f}};
  for (const CameraSpec& view : views) {
    const Camera camera = make_camera(view, 12, 12);
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x) {
        const Ray ray = camera_ray(camera, x + 0.5f, y + 0.5f);
        const Hit hit = intersect_closest(traced->accel, ray);
        ASSERT_TRUE(hit.found());
        const SurfacePoint sp = make_surface_point(traced->scene, ray, hit);
        ASSERT_TRUE(sp.front_face);
        const Estimate e = estimate_with_error(*traced, sp, options, 4000, static_cast<uint64_t>(y * 12 + x));
        expect_within_error(e, expected, "pixel " + std::to_string(x) + "," + std::to_string(y));
      }
  }
}

TEST_P(ClosedBox, DirectLightStaysRhoTimesLeWithABoundedErrorUpToTheEdgesAndCorners) {
  // Near an edge the adjacent wall lies close to the point's plane: area sampling's weight, area cos_l / d^2, grows
  // as 1 / distance^2 there (infinite variance as the point nears the edge), so those emitters are sampled by
  // solid angle. The estimate must stay rho Le, and its standard error stay small, at 0.1, 0.01 and 0.001 of the
  // box's half-width from an edge and from a corner.
  const Vec3 rho(0.5f, 0.7f, 0.3f), le(2.0f, 1.0f, 4.0f);
  const auto traced = prepare_scene(test::make_closed_emitting_box(1.0f, rho, le));
  DirectLightOptions options;
  options.strategy = GetParam();
  options.blinn_k = 1.0f;
  for (const float gap : {0.1f, 0.01f, 0.001f})
    for (const bool corner : {false, true}) {
      const Vec3 target(1.0f - gap, -1.0f, corner ? 1.0f - gap : 0.3f);  // on the floor, by the wall x = 1
      const Ray ray{Vec3(0.0f), target};
      const Hit hit = intersect_closest(traced->accel, ray);
      ASSERT_TRUE(hit.found());
      const SurfacePoint sp = make_surface_point(traced->scene, ray, hit);
      const Estimate e = estimate_with_error(*traced, sp, options, 4000, 7);
      const std::string where = std::string(corner ? "corner" : "edge") + ", gap " + std::to_string(gap);
      expect_within_error(e, rho * le, where);
      for (int c = 0; c < 3; ++c) EXPECT_LT(e.standard_error[c], 0.05f * rho[c] * le[c]) << where << " channel " << c;
    }
}

TEST_P(ClosedBox, RenderedFilmAveragesToRhoLe) {
  const Vec3 rho(0.6f), le(1.5f);
  const auto traced = prepare_scene(test::make_closed_emitting_box(2.0f, rho, le));
  RenderSettings settings;
  settings.width = settings.height = 24;
  settings.lights = GetParam();
  settings.blinn_k = 1.0f;
  settings.l1_rays = 8;
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  const Camera camera = make_camera({Vec3(0.0f), Vec3(0.0f, 0.0f, -1.0f), Vec3(0, 1, 0), 70.0f}, 24, 24);
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kSobol}) {
    settings.sampler = sampler;
    film.reset(settings);
    for (int f = 0; f < 32; ++f) render_frame(*traced, camera, settings, film, nullptr, pool);
    const Image l1 = pass_average(film, Pass::kL1);
    const Image le_pass = pass_average(film, Pass::kLe);
    double mean = 0.0;
    for (size_t i = 0; i < l1.rgb.size(); ++i) {
      mean += l1.rgb[i];
      EXPECT_FLOAT_EQ(le_pass.rgb[i], 1.5f);  // every pixel sees an emitting wall head-on
    }
    mean /= static_cast<double>(l1.rgb.size());
    // 24 x 24 x 3 channels x 256 samples each: the image mean is known to well under 1%.
    EXPECT_NEAR(mean, 0.9, 0.009) << kSamplerKindNames[static_cast<size_t>(sampler)];
  }
}

// A closed sphere of 4608 emitting triangles: L1 = rho Le at every point inside. Under `importance` its clusters are
// far larger than kMaxMembersByPower, so each shadow ray's emitter is found by descending a cluster's tree: the
// estimate must stay rho Le all over the wall.
TEST(ManyEmitters, ImportanceTreesKeepDirectLightInAClosedSphereAtRhoLe) {
  const Vec3 rho(0.5f, 0.7f, 0.3f), le(2.0f, 1.0f, 4.0f);
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 96, 24, rho, le));
  ASSERT_GT(traced->lights.size(), 4000u);
  ASSERT_FALSE(traced->lights.clusters.tree.empty());
  DirectLightOptions options;
  options.strategy = LightStrategy::kImportance;
  options.blinn_k = 1.0f;
  Pcg32 rng(3, 3);
  for (int point = 0; point < 6; ++point) {
    const float z = 2.0f * rng.next_float() - 1.0f, phi = 2.0f * kPi * rng.next_float();
    const float s = std::sqrt(1.0f - z * z);
    const Ray ray{Vec3(0.0f), Vec3(s * std::cos(phi), s * std::sin(phi), z)};
    const Hit hit = intersect_closest(traced->accel, ray);
    ASSERT_TRUE(hit.found());
    const SurfacePoint sp = make_surface_point(traced->scene, ray, hit);
    const Estimate e = estimate_with_error(*traced, sp, options, 4000, 11 + static_cast<uint64_t>(point));
    expect_within_error(e, rho * le, "point " + std::to_string(point));
  }
}

// 800 small emitting panels (1600 triangles) of four brightnesses, in one plane 0.3 above a floor (so that none
// shadows another): L1 on the floor is rho / pi x the sum of Lambert's formula over the panels. Under `importance`
// the trees inside the clusters find the panels near the point; choosing within clusters by power, as `power` does
// over all of them, spends most shadow rays on far panels, which leaves several times the noise.
TEST(ManyEmitters, ImportanceTreesMatchLambertUnderAGridOfPanelsWithLessNoiseThanPower) {
  Scene scene;
  scene.name = "panels";
  Material floor;
  floor.name = "floor";
  floor.kd = Vec3(0.6f, 0.5f, 0.4f);
  scene.materials.push_back(floor);
  for (int m = 0; m < 4; ++m) {
    Material light;
    light.name = "light" + std::to_string(m);
    light.kd = Vec3(0.0f);
    light.ke = Vec3(1.0f + 3.0f * static_cast<float>(m), 2.0f, 1.0f);
    scene.materials.push_back(light);
  }
  auto add_quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material) {
    const auto base = static_cast<uint32_t>(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {a, b, c, d});
    for (const auto& corners : {std::array<uint32_t, 3>{0, 1, 2}, std::array<uint32_t, 3>{0, 2, 3}}) {
      Triangle t;
      t.v[0] = base + corners[0], t.v[1] = base + corners[1], t.v[2] = base + corners[2];
      t.material = material;
      scene.triangles.push_back(t);
    }
  };
  const float f = 20.0f, height = 0.3f;
  add_quad({-f, 0, -f}, {-f, 0, f}, {f, 0, f}, {f, 0, -f}, 0);  // normal +y
  struct Panel {
    std::vector<glm::dvec3> corners;
    double le[3];
  };
  std::vector<Panel> panels;
  Pcg32 rng(8, 8);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 20; ++j) {
      // Cells of 0.15 x 0.2 over [-3, 3] x [-2, 2], each panel a random part of its cell.
      const float x0 = -3.0f + 0.15f * static_cast<float>(i), z0 = -2.0f + 0.2f * static_cast<float>(j);
      const float w = 0.15f * (0.2f + 0.7f * rng.next_float()), d = 0.2f * (0.2f + 0.7f * rng.next_float());
      const auto material = static_cast<uint32_t>(1 + (i * 7 + j * 3) % 4);
      const Vec3 a(x0, height, z0), b(x0 + w, height, z0), c(x0 + w, height, z0 + d), e(x0, height, z0 + d);
      add_quad(a, b, c, e, material);  // normal -y
      const Vec3 ke = scene.materials[material].ke;
      panels.push_back({{glm::dvec3(a), glm::dvec3(b), glm::dvec3(c), glm::dvec3(e)}, {ke.r, ke.g, ke.b}});
    }
  collect_emitters(scene);
  const auto traced = prepare_scene(std::move(scene));
  ASSERT_EQ(traced->lights.size(), 1600u);
  ASSERT_FALSE(traced->lights.clusters.tree.empty());
  DirectLightOptions options;
  options.blinn_k = 1.0f;
  for (const Vec3 at : {Vec3(0.0f), Vec3(-2.1f, 0.0f, 1.3f), Vec3(2.9f, 0.0f, -1.95f), Vec3(3.5f, 0.0f, 0.0f)}) {
    const std::optional<SurfacePoint> sp = test::surface_below(*traced, at, 0.1f);
    ASSERT_TRUE(sp.has_value());
    Vec3 expected(0.0f);
    for (const Panel& panel : panels)
      for (int c = 0; c < 3; ++c)
        expected[c] += static_cast<float>(
            test::lambert_irradiance(panel.corners, glm::dvec3(sp->position), glm::dvec3(0, 1, 0), panel.le[c]) / kPi);
    expected *= Vec3(0.6f, 0.5f, 0.4f);
    const std::string where = "floor at " + std::to_string(at.x) + ", " + std::to_string(at.z);
    options.strategy = LightStrategy::kImportance;
    const Estimate by_tree = estimate_with_error(*traced, *sp, options, 4000, 21);
    options.strategy = LightStrategy::kPower;
    const Estimate by_power = estimate_with_error(*traced, *sp, options, 4000, 21);
    expect_within_error(by_tree, expected, "importance, " + where);
    expect_within_error(by_power, expected, "power, " + where);
    EXPECT_LT(by_tree.standard_error.g, 0.5f * by_power.standard_error.g) << where;
  }
}

INSTANTIATE_TEST_SUITE_P(Lights, ClosedBox,
                         ::testing::Values(LightStrategy::kAll, LightStrategy::kUniform, LightStrategy::kArea,
                                           LightStrategy::kPower, LightStrategy::kImportance),
                         test::strategy_test_name);

TEST(DirectLight, MatchesLambertPolygonFormulaUnderARectangularLight) {
  const float w = 1.0f, h = 0.6f, height = 1.0f, rho = 0.8f, le = 5.0f;
  const auto traced = prepare_scene(test::make_rect_light_over_floor(w, h, height, Vec3(rho), Vec3(le)));
  const std::vector<glm::dvec3> light = {{-0.5 * w, height, -0.5 * h},
                                         {0.5 * w, height, -0.5 * h},
                                         {0.5 * w, height, 0.5 * h},
                                         {-0.5 * w, height, 0.5 * h}};
  for (const LightStrategy strategy : {LightStrategy::kAll, LightStrategy::kArea, LightStrategy::kImportance}) {
    for (const Vec3 p : {Vec3(0.0f), Vec3(0.3f, 0.0f, 0.1f), Vec3(1.2f, 0.0f, -0.4f), Vec3(-2.0f, 0.0f, 1.5f)}) {
      // The floor at p, seen straight from above.
      const std::optional<SurfacePoint> sp = test::surface_below(*traced, p, 0.5f);
      ASSERT_TRUE(sp);
      DirectLightOptions options;
      options.strategy = strategy;
      options.blinn_k = 1.0f;
      const Estimate e = estimate_with_error(*traced, *sp, options, 20000, 99);
      const double irradiance = test::lambert_irradiance(light, glm::dvec3(p), glm::dvec3(0, 1, 0), le);
      expect_within_error(e, Vec3(static_cast<float>(rho / kPi * irradiance)),
                          "point " + std::to_string(p.x) + "," + std::to_string(p.z));
      EXPECT_GT(e.mean.r, 0.0f);
    }
  }
}

// The default scene's ceiling beside the wall lamp, seen by pixels (110..150, 51) of a 256 x 256 render: only the
// lamp lights it (the ceiling light hangs below the ceiling and faces away), nothing stands between, so its L1 is
// Kd / pi times the lamp square's irradiance by Lambert's formula. Blender's Cycles 3.4 reads 4-35% low at these
// points (BENCHMARKS.md, "Time to quality against Cycles"); Lueur must not.
TEST(DirectLight, DefaultSceneCeilingBesideTheWallLampMatchesLambertsFormula) {
  const auto traced = prepare_scene(make_default_scene());
  const glm::dvec3 lamp_le(10.0, 18.0, 40.0), kd(0.725, 0.71, 0.68);
  const double z = 558.7;  // the lamp: a 100 mm square centred on (150, 430), facing -z
  const std::vector<glm::dvec3> lamp = {{200, 380, z}, {100, 380, z}, {100, 480, z}, {200, 480, z}};
  for (const float x : {341.1f, 269.0f, 196.9f}) {
    Ray ray;  // straight up onto the ceiling at (x, 492.1)
    ray.origin = Vec3(x, 500.0f, 492.1f);
    ray.dir = Vec3(0.0f, 1.0f, 0.0f);
    const Hit hit = intersect_closest(traced->accel, ray);
    ASSERT_TRUE(hit.found());
    const SurfacePoint sp = make_surface_point(traced->scene, ray, hit);
    ASSERT_NEAR(sp.position.y, 548.8f, 1e-3f);
    for (const LightStrategy strategy : {LightStrategy::kArea, LightStrategy::kImportance}) {
      DirectLightOptions options;
      options.strategy = strategy;
      options.blinn_k = 1.0f;
      const Estimate e = estimate_with_error(*traced, sp, options, 40000, 5);
      const double irradiance = test::lambert_irradiance(lamp, glm::dvec3(sp.position), glm::dvec3(0, -1, 0), 1.0);
      const glm::dvec3 expected = kd / static_cast<double>(kPi) * lamp_le * irradiance;
      expect_within_error(e, Vec3(expected),
                          "ceiling x = " + std::to_string(x) + ", lights " +
                              std::string(kLightStrategyNames[static_cast<size_t>(strategy)]));
      EXPECT_GT(e.mean.b, 0.1f);
    }
  }
}

TEST(DirectLight, BlinnPhongMixWithKOneIsLambertAndLobeIsNormalised) {
  Material m;
  m.kd = Vec3(0.5f);
  m.ns = 20.0f;
  const Vec3 n(0, 0, 1), wi = glm::normalize(Vec3(0.3f, 0.1f, 1.0f)), wo = glm::normalize(Vec3(-0.2f, 0.4f, 1.0f));
  EXPECT_FLOAT_EQ(eval_brdf(m, m.kd, n, wi, wo, 1.0f).r, 0.5f * kInvPi);
  // K = 0: pure lobe; at the mirror configuration cos(theta_h) = 1 and the lobe is (n + 8) / (8 pi).
  const Vec3 mirror(-wi.x, -wi.y, wi.z);
  EXPECT_NEAR(eval_brdf(m, m.kd, n, wi, mirror, 0.0f).r, 0.5f * 28.0f / (8.0f * kPi), 1e-5f);
  // With Ks the mix is not used: Kd / pi + Ks lobe.
  m.ks = Vec3(0.25f);
  EXPECT_NEAR(eval_brdf(m, m.kd, n, wi, mirror, 0.7f).r, 0.5f * kInvPi + 0.25f * 28.0f / (8.0f * kPi), 1e-5f);
}

// L1 recomputed at several bounce hits at once (their samples sharing a batch's lanes) must be what a call per point
// gives, byte for byte, and trace the same rays: for every strategy (kAll and the head-light fall back on a call per
// point), ray counts that fill a batch exactly, unevenly or not at all, the whole BRDF or its view-dependent part,
// both samplers, and points on a black emitter (which reflect nothing and take no lanes).
TEST(DirectLight, SeveralPointsAtOnceGiveWhatOnePointAtATimeGives) {
  Scene scene = make_default_scene();
  for (Material& m : scene.materials)
    if (m.name == "wall-lamp") m.kd = Vec3(0.0f);  // a black emitter: no L1 to estimate there
  const auto traced = prepare_scene(std::move(scene));
  std::vector<SurfacePoint> surface_points;
  bool saw_emitter = false;
  const Vec3 centre(278.0f, 274.0f, 280.0f);
  for (int i = 0; i < 40; ++i) {  // a spiral of directions over the sphere
    const float z = 1.0f - (2.0f * static_cast<float>(i) + 1.0f) / 40.0f, phi = 2.39996f * static_cast<float>(i);
    const float r = std::sqrt(1.0f - z * z);
    Ray ray;
    ray.origin = centre;
    ray.dir = Vec3(r * std::cos(phi), z, r * std::sin(phi));
    const Hit hit = intersect_closest(traced->accel, ray);
    if (!hit.found()) continue;
    surface_points.push_back(make_surface_point(traced->scene, ray, hit));
    saw_emitter |= !reflects_light(traced->scene.material_of(hit.triangle));
  }
  Ray toward_lamp;  // and the lamp itself (a square of 100 mm centred on (150, 430) at z = 558.7, facing -z)
  toward_lamp.origin = Vec3(150.0f, 430.0f, 500.0f);
  toward_lamp.dir = Vec3(0.0f, 0.0f, 1.0f);
  const Hit lamp = intersect_closest(traced->accel, toward_lamp);
  ASSERT_TRUE(lamp.found());
  surface_points.insert(surface_points.begin() + 3, make_surface_point(traced->scene, toward_lamp, lamp));
  saw_emitter |= !reflects_light(traced->scene.material_of(lamp.triangle));
  ASSERT_GE(surface_points.size(), 30u);
  EXPECT_TRUE(saw_emitter);

  std::vector<const SurfacePoint*> points;
  std::vector<uint64_t> first_samples;
  for (size_t i = 0; i < surface_points.size(); ++i) {
    points.push_back(&surface_points[i]);
    first_samples.push_back(first_sample_of_run(3 * i + 1, 16));
  }
  const EmitterRecord head_light = make_camera_light(
      make_camera({Vec3(278, 273, -800), Vec3(278, 273, 0), Vec3(0, 1, 0), 40.0f}, 64, 64), traced->diagonal);
  for (const SamplerKind kind : {SamplerKind::kSobol, SamplerKind::kIndependent})
    for (const LightStrategy strategy : {LightStrategy::kArea, LightStrategy::kUniform, LightStrategy::kPower,
                                         LightStrategy::kAll, LightStrategy::kImportance})
      for (const int rays : {1, 2, 3, 5, 16, 17})
        for (const bool with_head_light : {false, true})
          for (const bool specular_only : {false, true}) {
            DirectLightOptions options;
            options.strategy = strategy;
            options.rays = rays;
            options.camera_light = with_head_light ? &head_light : nullptr;
            options.specular_only = specular_only;
            const std::string where = "sampler " + std::to_string(static_cast<int>(kind)) + ", strategy " +
                                      std::to_string(static_cast<int>(strategy)) + ", " + std::to_string(rays) +
                                      " rays" + (with_head_light ? ", head-light" : "") +
                                      (specular_only ? ", specular part only" : "");
            PixelSampler one_sampler(kind, 9, 1234, 5, RngPurpose::kRecompute);
            PixelSampler many_sampler(kind, 9, 1234, 5, RngPurpose::kRecompute);
            uint64_t one_rays = 0, many_rays = 0;
            std::vector<Vec3> l1(points.size()), arriving(points.size());
            estimate_direct_light_at_points(*traced, points.data(), first_samples.data(), points.size(), options,
                                            many_sampler, many_rays, l1.data(), arriving.data());
            for (size_t i = 0; i < points.size(); ++i) {
              Vec3 one_arriving(0.0f);
              const Vec3 one = estimate_direct_light(*traced, *points[i], options, one_sampler, first_samples[i],
                                                     one_rays, nullptr, &one_arriving);
              ASSERT_EQ(l1[i], one) << where << ", point " << i;
              ASSERT_EQ(arriving[i], one_arriving) << where << ", point " << i;
            }
            EXPECT_EQ(many_rays, one_rays) << where;
            EXPECT_GT(many_rays, 0u) << where;
          }
}

}  // namespace
}  // namespace lueur
