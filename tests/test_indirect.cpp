// L2 and AO against closed forms, the reuse modes against each other, where reuse happens, and anti-aliasing.
#include <gtest/gtest.h>

#include <algorithm>

#include "obj_test_support.h"
#include "integrator/indirect_light.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

/// Renders `frames` frames and returns, per pixel, the mean and standard error of one layer's red channel over
/// the frames (each frame's value is the difference of the sums before and after it).
struct PixelStats {
  std::vector<double> mean, standard_error;
};
PixelStats render_layer_stats(const TracedScene& traced, const CameraSpec& view, const RenderSettings& settings,
                              Layer layer, int frames, int channel = 0) {
  Film film;
  film.reset(settings);
  L1Cache store;
  store.reset(l1_store_bytes(settings));
  ThreadPool pool(2);
  const Camera camera = make_camera(view, settings.width, settings.height);
  const size_t n = film.pixel_count();
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  std::vector<float> before(film.sums[static_cast<size_t>(layer)]);
  for (int f = 0; f < frames; ++f) {
    render_frame(traced, camera, settings, film, &store, pool);
    const auto& after = film.sums[static_cast<size_t>(layer)];
    for (size_t i = 0; i < n; ++i) {
      const double x = static_cast<double>(after[3 * i + static_cast<size_t>(channel)]) -
                       static_cast<double>(before[3 * i + static_cast<size_t>(channel)]);
      sum[i] += x;
      sum2[i] += x * x;
    }
    before = after;
  }
  PixelStats stats;
  for (size_t i = 0; i < n; ++i) {
    const double mean = sum[i] / frames;
    stats.mean.push_back(mean);
    stats.standard_error.push_back(std::sqrt(std::max(0.0, sum2[i] / frames - mean * mean) / (frames - 1)));
  }
  return stats;
}

/// Per pixel, the mean of one layer's red channel over `runs` renders of `frames_per_run` frames with seeds 1, 2, ...,
/// and its standard error. The frames of one run need not be independent: with the L1 store a frame takes cells that
/// earlier frames filled, with `average` a running mean of the screen. Their spread then understates the error of
/// their mean, and independent runs measure by how much: the runs' means spread (pooled over the pixels) by more
/// than the frames' spread within the runs predicts. Each pixel's error is its frames' spread widened by that factor
/// (never narrowed: with Sobol points the frames are one stratified sequence and their spread overstates the
/// error, which leaves the bound valid).
struct ReplicatedStats {
  std::vector<double> mean, standard_error;
  double correlation_factor = 1.0;  ///< the runs' measured variance over what the frames' spread predicts
};
ReplicatedStats render_replicated_stats(const TracedScene& traced, const CameraSpec& view, RenderSettings settings,
                                        Layer layer, int runs, int frames_per_run) {
  std::vector<PixelStats> run_stats;
  for (int r = 0; r < runs; ++r) {
    settings.seed = static_cast<uint64_t>(r + 1);
    run_stats.push_back(render_layer_stats(traced, view, settings, layer, frames_per_run));
  }
  const size_t n = run_stats[0].mean.size();
  ReplicatedStats stats;
  stats.mean.assign(n, 0.0);
  std::vector<double> predicted(n, 0.0);  // per pixel, the variance of one run's mean that its frames predict
  for (const PixelStats& run : run_stats)
    for (size_t i = 0; i < n; ++i) {
      stats.mean[i] += run.mean[i] / runs;
      predicted[i] += run.standard_error[i] * run.standard_error[i] / runs;
    }
  double measured_sum = 0.0, predicted_sum = 0.0;
  for (const PixelStats& run : run_stats)
    for (size_t i = 0; i < n; ++i) measured_sum += (run.mean[i] - stats.mean[i]) * (run.mean[i] - stats.mean[i]);
  for (size_t i = 0; i < n; ++i) predicted_sum += predicted[i];
  stats.correlation_factor = std::max(1.0, measured_sum / (runs - 1) / predicted_sum);
  for (size_t i = 0; i < n; ++i)
    stats.standard_error.push_back(std::sqrt(predicted[i] * stats.correlation_factor / runs));
  return stats;
}

class ClosedBoxL2 : public ::testing::TestWithParam<ReuseMode> {};

TEST_P(ClosedBoxL2, IsRhoSquaredLeAtEveryPixel) {
  // A closed sphere rather than a box: in a box, points near an edge see the adjacent wall at d -> 0 and the
  // estimators' variance is unbounded, so no finite-sample tolerance is trustworthy. The closed form is the same
  // for any closed enclosure.
  const float rho = 0.6f, le = 2.0f;
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 32, 16, Vec3(rho), Vec3(le)));
  for (uint32_t t = 0; t < traced->scene.triangles.size(); ++t)
    ASSERT_LT(glm::dot(traced->scene.geometric_normal_raw(t), traced->scene.point(t, 0.3f, 0.3f)), 0.0f);
  RenderSettings settings;
  settings.width = settings.height = 12;
  settings.enabled = {false, false, true, false};
  settings.reuse = GetParam();
  settings.blinn_k = 1.0f;
  settings.l1_rays = 8;
  settings.l2_rays = 8;
  const CameraSpec view{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f};
  const double expected = rho * rho * le;
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kSobol}) {
    settings.sampler = sampler;
    const std::string name(kSamplerKindNames[static_cast<size_t>(sampler)]);
    // Eight independent runs of 25 frames (each through the store's generations of frames 0-3 and 4-31).
    const ReplicatedStats stats = render_replicated_stats(*traced, view, settings, Layer::kL2, 8, 25);
    for (size_t i = 0; i < stats.mean.size(); ++i)
      EXPECT_NEAR(stats.mean[i], expected, 5.0 * stats.standard_error[i] + 1e-4)
          << name << ", pixel " << i << " (the runs spread " << stats.correlation_factor << "x as the frames predict)";
    // And the closed box's image mean (edges included) within 2%.
    const auto box = prepare_scene(test::make_closed_emitting_box(1.0f, Vec3(rho), Vec3(le)));
    const PixelStats box_stats = render_layer_stats(*box, view, settings, Layer::kL2, 100);
    double mean = 0.0;
    for (const double m : box_stats.mean) mean += m;
    // The L1 store shares each cell's estimate among every bounce hit that looks it up, and near the box's edges
    // those estimates are heavy-tailed: over 8 seeds x 300 frames the image mean spread by 0.016 with the store
    // against 0.008 without, around the same centre (0.711 and 0.714), so its bound is wider.
    const double tolerance = uses_cache(GetParam()) ? 0.05 : 0.02;
    EXPECT_NEAR(mean / static_cast<double>(box_stats.mean.size()), expected, tolerance * expected) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Reuse, ClosedBoxL2,
                         ::testing::Values(ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kAverage, ReuseMode::kCache,
                                           ReuseMode::kScreenCache),
                         [](const auto& param_info) {
                           std::string name(kReuseModeNames[static_cast<size_t>(param_info.param)]);
                           std::replace(name.begin(), name.end(), '+', '_');  // test names: letters, digits, _
                           return name;
                         });

// An MTL without Ns gives the lobe exponent 0, with which the report's mix is Lambert whatever K: a closed box of
// albedo rho read from a file gives L1 = rho Le and L2 = rho^2 Le with the default settings (K = 0.7, smooth normals
// on). tinyobjloader reads a missing Ns as 1, and that faint lobe lost energy: the image means were 1.1% (L1) and
// 3.3% (L2) low.
TEST(ClosedBoxFromAFile, AnMtlWithoutNsGivesTheClosedFormsWithTheDefaultSettings) {
  const std::string dir = test::make_temp_dir("closed-box-file");
  test::write_text(dir, "box.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  // The cube [-1, 1]^3, each face counter-clockwise seen from inside (obj_test_support.h's cube faces outwards).
  const std::string path = test::write_text(dir, "box.obj",
                                            "mtllib box.mtl\n"
                                            "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                            "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                            "usemtl wall\n"
                                            "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n");
  const auto traced = prepare_scene(load_obj(path).scene);
  ASSERT_EQ(traced->scene.emitters.size(), 12u);
  EXPECT_EQ(traced->scene.materials.front().ns, 0.0f);
  RenderSettings settings;  // the defaults, but for the size and the passes
  ASSERT_LT(settings.blinn_k, 1.0f);
  settings.width = settings.height = 24;
  settings.enabled = {false, true, true, false};
  const CameraSpec view{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f};
  const auto image_mean = [&](Layer layer) {
    const PixelStats stats = render_layer_stats(*traced, view, settings, layer, 48);
    double sum = 0.0;
    for (const double m : stats.mean) sum += m;
    return sum / static_cast<double>(stats.mean.size());
  };
  // Measured over four seeds: within 0.2% (L1) and 0.3% (L2) of the closed forms.
  EXPECT_NEAR(image_mean(Layer::kL1), 0.5, 0.005 * 0.5);
  EXPECT_NEAR(image_mean(Layer::kL2), 0.25, 0.015 * 0.25);
}

TEST(AmbientOcclusion, IsAlbedoWithNothingWithinTheRadius) {
  const auto traced =
      prepare_scene(test::make_rect_light_over_floor(0.2f, 0.2f, 5.0f, Vec3(0.3f, 0.5f, 0.7f), Vec3(1.0f)));
  Ray ray;
  ray.origin = Vec3(2.0f, 1.0f, 0.0f);
  ray.dir = Vec3(0.0f, -1.0f, 0.0f);
  const SurfacePoint sp = make_surface_point(traced->scene, ray, intersect_closest(traced->accel, ray));
  PixelSampler sampler(SamplerKind::kSobol, 1, 2, 0, RngPurpose::kOcclusion);
  uint64_t rays = 0;
  const Vec3 ao = estimate_ambient_occlusion(*traced, sp, 4096, 4.0f, sampler, 0, rays);
  EXPECT_EQ(ao, Vec3(0.3f, 0.5f, 0.7f));
  EXPECT_EQ(rays, 4096u);
}

TEST(AmbientOcclusion, UnderACeilingIsAlbedoTimesHOverRSquared) {
  // A ray at angle theta reaches the ceiling at distance H / cos(theta); it travels farther than R when
  // cos(theta) < H / R, a cosine-weighted fraction of (H / R)^2.
  const float height = 1.0f, radius = 2.0f, kd = 0.8f;
  const auto traced = prepare_scene(test::make_rect_light_over_floor(400.0f, 400.0f, height, Vec3(kd), Vec3(1.0f)));
  Ray ray;
  ray.origin = Vec3(0.0f, 0.5f, 0.0f);
  ray.dir = Vec3(0.0f, -1.0f, 0.0f);
  const SurfacePoint sp = make_surface_point(traced->scene, ray, intersect_closest(traced->accel, ray));
  PixelSampler sampler(SamplerKind::kIndependent, 3, 4, 0, RngPurpose::kOcclusion);  // binomial error below
  uint64_t rays = 0;
  constexpr int kRays = 200000;
  const float ao = estimate_ambient_occlusion(*traced, sp, kRays, radius, sampler, 0, rays).r;
  const double p = (height / radius) * (height / radius);
  EXPECT_NEAR(ao, kd * p, 5.0 * kd * std::sqrt(p * (1 - p) / kRays));
}

std::shared_ptr<const TracedScene> default_traced() {
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  return prepare_scene(std::move(scene));
}

CameraSpec default_view() { return default_scene_camera(); }

TEST(ReuseModes, AgreeWithinNoiseOnDiffuseSurfaces) {
  const auto traced = default_traced();
  RenderSettings settings;
  // Reuse takes L1 from a point up to a pixel away, so its (spatial) bias shrinks with the pixel size: compare at
  // a resolution where a pixel is a few millimetres.
  constexpr int kSize = 96, kBlock = 24;
  settings.width = settings.height = kSize;
  settings.enabled = {false, false, true, false};
  settings.blinn_k = 1.0f;  // Lambertian walls: reusing their L1 toward another direction is exact
  settings.l1_rays = 4;
  settings.l2_rays = 8;
  std::vector<PixelStats> results;
  for (const ReuseMode mode : {ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kAverage}) {
    settings.reuse = mode;
    results.push_back(render_layer_stats(*traced, default_view(), settings, Layer::kL2, 24, 1));
  }
  // Compare blocks of pixels on Lambertian surfaces (not the apple, whose Ks makes L1 view-dependent).
  const Camera camera = make_camera(default_view(), kSize, kSize);
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      std::array<double, 3> mean{}, variance{};
      int pixels = 0;
      for (int y = by * kBlock; y < (by + 1) * kBlock; ++y)
        for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
          const Hit hit = intersect_closest(traced->accel, camera_ray(camera, x + 0.5f, y + 0.5f));
          if (!hit.found() || traced->scene.material_of(hit.triangle).has_specular()) continue;
          const size_t i = static_cast<size_t>(y * kSize + x);
          for (size_t m = 0; m < 3; ++m) {
            mean[m] += results[m].mean[i];
            variance[m] += results[m].standard_error[i] * results[m].standard_error[i];
          }
          ++pixels;
        }
      if (pixels < 16) continue;
      for (size_t m = 1; m < 3; ++m) {
        const double tolerance = 5.0 * std::sqrt(variance[0] + variance[m]) / pixels + 1e-4;
        EXPECT_NEAR(mean[m] / pixels, mean[0] / pixels, tolerance) << "block " << bx << "," << by << " mode " << m;
      }
    }
}

TEST(ReuseModes, ReuseHappensWhereTheCameraSeesQAndNeverBehindTheBlocks) {
  const auto traced = default_traced();
  const int w = 128, h = 128;
  const Camera camera = make_camera(default_view(), w, h);
  ScreenBuffer screen;
  screen.resize(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Ray ray = camera_ray(camera, x + 0.5f, y + 0.5f);
      const Hit hit = intersect_closest(traced->accel, ray);
      if (!hit.found()) continue;
      const size_t i = static_cast<size_t>(y * w + x);
      screen.triangle[i] = hit.triangle;
      screen.pixels[i].position = traced->scene.point(hit.triangle, hit.u, hit.v);
    }
  // Random points, uniform by area over the scene: those the camera sees directly are reused almost always (misses
  // only where a pixel straddles two triangles); those it cannot see (behind the blocks, their back faces) are
  // reused only where they lie within a pixel of a silhouette.
  std::vector<double> cdf;
  double total = 0.0;
  for (uint32_t t = 0; t < traced->scene.triangles.size(); ++t) cdf.push_back(total += traced->scene.area(t));
  Pcg32 rng(8, 8);
  int visible = 0, visible_reused = 0, hidden = 0, hidden_reused = 0;
  for (int s = 0; s < 40000; ++s) {
    const auto tri =
        static_cast<uint32_t>(std::upper_bound(cdf.begin(), cdf.end(), rng.next_float() * total) - cdf.begin());
    const float r1 = std::sqrt(rng.next_float()), r2 = rng.next_float();
    const Vec3 q = traced->scene.point(tri, r1 * (1 - r2), r1 * r2);
    Ray to_q;
    to_q.origin = camera.eye;
    to_q.dir = q - camera.eye;
    to_q.tmax = 1.0f + 1e-3f;
    const Hit first = intersect_closest(traced->accel, to_q);
    float px = 0, py = 0;
    if (!project_to_pixel(camera, q, px, py)) continue;
    const bool seen = first.found() && first.triangle == tri && first.t > 0.999f;
    const Vec3 normal = glm::normalize(traced->scene.geometric_normal_raw(tri));
    const bool reused = find_reusable_pixel(camera, screen, tri, q, normal) >= 0;
    if (seen) {
      ++visible;
      visible_reused += reused;
    } else if (!first.found() || first.t < 0.99f) {
      ++hidden;
      hidden_reused += reused;
    }
  }
  ASSERT_GT(visible, 1000);
  ASSERT_GT(hidden, 1000);
  EXPECT_GT(static_cast<double>(visible_reused) / visible, 0.95);
  EXPECT_LT(static_cast<double>(hidden_reused) / hidden, 0.01);
}

TEST(ReuseModes, ReuseFractionLayerIsHighOnTheDefaultView) {
  const auto traced = default_traced();
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.l1_rays = 2;
  settings.l2_rays = 1;  // one bounce a pixel: its share of hits served is that bounce's 0 or 1 (see the mean below)
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  const FrameResult r = render_frame(*traced, make_camera(default_view(), 32, 32), settings, film, nullptr, pool);
  ASSERT_GT(r.l2_bounce_hits, 0u);
  const double fraction = static_cast<double>(r.l2_reused) / static_cast<double>(r.l2_bounce_hits);
  EXPECT_GT(fraction, 0.5);
  EXPECT_LT(fraction, 1.0);  // some bounce rays reach surfaces the camera does not see
  // Red: the share of a pixel's bounce hits served by the screen; green (the L1 store) is 0 here; the three add to 1
  // wherever a bounce ray hit something.
  const Image layer = layer_average(film, Layer::kReuseFraction);
  double served_by_screen = 0.0;
  int hit_pixels = 0;
  for (size_t i = 0; i < layer.rgb.size(); i += 3) {
    EXPECT_EQ(layer.rgb[i + 1], 0.0f);
    const float total = layer.rgb[i] + layer.rgb[i + 1] + layer.rgb[i + 2];
    if (total > 0.0f) {
      EXPECT_NEAR(total, 1.0f, 1e-5f);
      served_by_screen += layer.rgb[i];
      ++hit_pixels;
    }
  }
  // Each pixel whose bounce hit something is one of the frame's bounce hits, served by the screen (red 1) or not:
  // the mean red over them is the frame's share, exactly.
  EXPECT_EQ(static_cast<uint64_t>(hit_pixels), r.l2_bounce_hits);
  EXPECT_NEAR(served_by_screen / hit_pixels, fraction, 1e-5);
  // The two explanatory layers add up to L2.
  const Image l2 = layer_average(film, Layer::kL2), reused = layer_average(film, Layer::kL2Reused),
              recomputed = layer_average(film, Layer::kL2Recomputed);
  for (size_t i = 0; i < l2.rgb.size(); ++i) EXPECT_NEAR(l2.rgb[i], reused.rgb[i] + recomputed.rgb[i], 1e-5f);
}

TEST(AntiAliasing, JitteredFramesConvergeToTheMeanOfBothSidesOfAnEdge) {
  // An emitting half-plane x < 0 facing the camera at z = -1; the camera at the origin looks down -z. With an odd
  // image width the edge x = 0 cuts the middle pixel in half.
  Scene scene;
  Material light;
  light.ke = Vec3(1.0f);
  scene.materials = {light};
  scene.positions = {Vec3(-100, -100, -1), Vec3(0, -100, -1), Vec3(0, 100, -1), Vec3(-100, 100, -1)};
  Triangle t1, t2;
  t1.v[0] = 0, t1.v[1] = 1, t1.v[2] = 2;
  t2.v[0] = 0, t2.v[1] = 2, t2.v[2] = 3;
  scene.triangles = {t1, t2};
  collect_emitters(scene);
  const auto traced = prepare_scene(std::move(scene));
  RenderSettings settings;
  settings.width = 9;
  settings.height = 1;
  settings.enabled = {true, false, false, false};
  Film film;
  film.reset(settings);
  ThreadPool pool(1);
  // Camera right is -x here? Use a view whose right vector is +x: looking down -z with up +y.
  const Camera camera = make_camera({Vec3(0.0f), Vec3(0, 0, -1), Vec3(0, 1, 0), 10.0f}, 9, 1);
  constexpr int kFrames = 4096;
  for (int f = 0; f < kFrames; ++f) render_frame(*traced, camera, settings, film, nullptr, pool);
  const Image le = layer_average(film, Layer::kLe);
  EXPECT_FLOAT_EQ(le.at(0, 0).r, 1.0f);  // fully on the emitter
  EXPECT_FLOAT_EQ(le.at(8, 0).r, 0.0f);  // fully off it
  EXPECT_NEAR(le.at(4, 0).r, 0.5f, 4.0f * std::sqrt(0.25f / kFrames));
}

}  // namespace
}  // namespace lueur
