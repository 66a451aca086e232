// ln, the light of the second and later bounces, against closed forms: inside a closed emitting sphere of albedo
// rho and emission Le every bounce adds rho^(k + 1) Le, so ln with --max-bounces N is rho^3 Le (1 - rho^(N - 1)) /
// (1 - rho), and Le + L1 + L2 + ln the whole series Le / (1 - rho). Every vertex there finds light both by its
// shadow ray and by its bounce direction: the weights of the two must add up to one. Also: the camera's mirrors
// and glass count against the bounce limit, and the pass's bytes do not depend on the thread count.
#include <gtest/gtest.h>

#include <cmath>

#include "integrator/renderer.h"
#include "test_support.h"

namespace lueur {
namespace {

constexpr float kRho = 0.6f, kLe = 2.0f;

/// The image mean of each pass (red channel) after `frames` frames.
std::array<double, kPassCount> pass_means(const TracedScene& traced, const CameraSpec& view,
                                          const RenderSettings& settings, int frames, int threads = 2) {
  Accumulation accumulation;
  accumulation.reset(settings);
  ThreadPool pool(threads);
  const Camera camera = make_camera(view, settings.width, settings.height);
  for (int f = 0; f < frames; ++f) render_frame(traced, camera, settings, accumulation, pool);
  std::array<double, kPassCount> means{};
  for (int p = 0; p < kPassCount; ++p) {
    if (!settings.enabled[static_cast<size_t>(p)]) continue;
    const Image image = pass_average(accumulation.film, static_cast<Pass>(p));
    double sum = 0.0;
    for (size_t i = 0; i < image.rgb.size(); i += 3) sum += image.rgb[i];
    means[static_cast<size_t>(p)] = sum / static_cast<double>(image.rgb.size() / 3);
  }
  return means;
}

const CameraSpec kInside{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f};

/// Every light pass on (AO off), Lambert everywhere, few rays of each kind.
RenderSettings light_passes(int max_bounces) {
  RenderSettings settings;
  settings.width = settings.height = 12;
  settings.enabled = {true, true, true, false, true};
  settings.blinn_k = 1.0f;
  settings.l1_rays = 4;
  settings.l2_rays = 4;
  settings.ln_rays = 8;
  settings.max_bounces = max_bounces;
  return settings;
}

double expected_ln(int max_bounces) {
  const double rho = kRho;
  return rho * rho * rho * kLe * (1.0 - std::pow(rho, max_bounces - 1)) / (1.0 - rho);
}

TEST(FurtherBounces, InAClosedEmittingSphereLnIsTheSeriesFromTheThirdBounceOn) {
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 32, 16, Vec3(kRho), Vec3(kLe)));
  for (const int n : {2, 3, 8, 1024}) {  // 1024: no cap that matters (rho^1023 is nothing)
    const auto means = pass_means(*traced, kInside, light_passes(n), 64);
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kLn)], expected_ln(n), 0.01 * expected_ln(n)) << n << " bounces";
    // The report's passes keep their meaning beside it.
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kL1)], kRho * kLe, 0.01 * kRho * kLe);
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kL2)], kRho * kRho * kLe, 0.01 * kRho * kRho * kLe);
    if (n == 1024) {
      const double total = means[0] + means[1] + means[2] + means[4];
      EXPECT_NEAR(total, kLe / (1.0 - kRho), 0.01 * kLe / (1.0 - kRho)) << "the full series";
    }
  }
  // ln alone: its paths leave along bounces of their own instead of L2's, to the same value.
  RenderSettings alone = light_passes(8);
  alone.enabled = {false, false, false, false, true};
  const double ln_alone = pass_means(*traced, kInside, alone, 64)[static_cast<size_t>(Pass::kLn)];
  EXPECT_NEAR(ln_alone, expected_ln(8), 0.01 * expected_ln(8)) << "without L2";
}

// A caustic: a lamp that faces up, under a mirror ceiling, lights the floor only through the mirror. No shadow ray
// can find that light (L1 and L2 are 0); ln's bounce directions do. With two bounces (the floor's, the mirror's) the
// floor reads rho / pi x Ks x the irradiance of the lamp's mirror image (Lambert's polygon formula), wherever the
// lamp itself does not stand between the floor and the mirror's image of it.
TEST(FurtherBounces, ALampSeenOnlyInAMirrorLightsTheFloorInLn) {
  const float rho = 0.5f, ks = 0.8f, le = 5.0f;
  Scene s;
  Material floor, mirror, lamp;
  floor.kd = Vec3(rho);
  mirror.surface = SurfaceKind::kMirror;
  mirror.kd = Vec3(0.0f);
  mirror.ks = Vec3(ks);
  lamp.kd = Vec3(0.0f);
  lamp.ke = Vec3(le);
  s.materials = {floor, mirror, lamp};
  add_quad(s, Vec3(-20, -20, 0), Vec3(20, -20, 0), Vec3(20, 20, 0), Vec3(-20, 20, 0), 0);  // facing up
  add_quad(s, Vec3(-20, -20, 2), Vec3(-20, 20, 2), Vec3(20, 20, 2), Vec3(20, -20, 2), 1);  // facing down
  add_quad(s, Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(1, 1, 1), Vec3(-1, 1, 1), 2);          // facing up
  collect_emitters(s);
  const auto traced = prepare_scene(s);
  RenderSettings settings = light_passes(2);
  settings.width = settings.height = 8;
  settings.ln_rays = 64;
  // Looking down at floor points about x = 5, beyond twice the lamp's half-width: none of their rays toward the
  // mirror's image of the lamp passes through the lamp.
  const CameraSpec view{Vec3(5, 0, 1.5f), Vec3(5, 0, 0), Vec3(0, 1, 0), 8.0f};
  const auto means = pass_means(*traced, view, settings, 256);
  EXPECT_EQ(means[static_cast<size_t>(Pass::kL1)], 0.0);
  EXPECT_EQ(means[static_cast<size_t>(Pass::kL2)], 0.0);
  // The expected value, averaged over the floor points the pixels' centres see.
  const Camera camera = make_camera(view, settings.width, settings.height);
  const std::vector<glm::dvec3> image_of_lamp = {{-1, -1, 3}, {-1, 1, 3}, {1, 1, 3}, {1, -1, 3}};  // facing down
  double expected = 0.0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const Ray ray = camera_ray(camera, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const glm::dvec3 point = glm::dvec3(ray.origin) - glm::dvec3(ray.dir) * double(ray.origin.z / ray.dir.z);
      expected += rho / kPi * ks * test::lambert_irradiance(image_of_lamp, point, glm::dvec3(0, 0, 1), le);
    }
  expected /= settings.width * settings.height;
  // About 8x8 x 64 x 256 paths, one in a hundred of which meets the lamp: within 1%, at 3%.
  EXPECT_NEAR(means[static_cast<size_t>(Pass::kLn)], expected, 0.03 * expected);
}

TEST(FurtherBounces, OneBounceIsLeL1AndL2AndLnCarriesNothing) {
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 32, 16, Vec3(kRho), Vec3(kLe)));
  const auto means = pass_means(*traced, kInside, light_passes(1), 4);
  EXPECT_EQ(means[static_cast<size_t>(Pass::kLn)], 0.0);
  EXPECT_GT(means[static_cast<size_t>(Pass::kL2)], 0.0);
}

TEST(FurtherBounces, AreTheSameBytesForAnyThreadCount) {
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 16, 8, Vec3(kRho), Vec3(kLe)));
  RenderSettings settings = light_passes(6);
  settings.width = 20;
  settings.height = 18;
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kSobol}) {
    settings.sampler = sampler;
    std::vector<float> first;
    for (const int threads : {1, 2, 5}) {
      Accumulation accumulation;
      accumulation.reset(settings);
      ThreadPool pool(threads);
      const Camera camera = make_camera(kInside, settings.width, settings.height);
      for (int f = 0; f < 3; ++f) render_frame(*traced, camera, settings, accumulation, pool);
      const auto& sums = accumulation.film.sums[static_cast<size_t>(Layer::kLn)];
      if (first.empty())
        first = sums;
      else
        EXPECT_EQ(sums, first) << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace lueur
