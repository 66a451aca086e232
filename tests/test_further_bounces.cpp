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

RenderSettings closed_sphere_settings(int max_bounces) {
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
    const auto means = pass_means(*traced, kInside, closed_sphere_settings(n), 64);
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kLn)], expected_ln(n), 0.01 * expected_ln(n)) << n << " bounces";
    // The report's passes keep their meaning beside it.
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kL1)], kRho * kLe, 0.01 * kRho * kLe);
    EXPECT_NEAR(means[static_cast<size_t>(Pass::kL2)], kRho * kRho * kLe, 0.01 * kRho * kRho * kLe);
    if (n == 1024) {
      const double total = means[0] + means[1] + means[2] + means[4];
      EXPECT_NEAR(total, kLe / (1.0 - kRho), 0.01 * kLe / (1.0 - kRho)) << "the full series";
    }
  }
}

TEST(FurtherBounces, OneBounceIsLeL1AndL2AndLnCarriesNothing) {
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 32, 16, Vec3(kRho), Vec3(kLe)));
  const auto means = pass_means(*traced, kInside, closed_sphere_settings(1), 4);
  EXPECT_EQ(means[static_cast<size_t>(Pass::kLn)], 0.0);
  EXPECT_GT(means[static_cast<size_t>(Pass::kL2)], 0.0);
}

TEST(FurtherBounces, AreTheSameBytesForAnyThreadCount) {
  const auto traced = prepare_scene(test::make_closed_emitting_sphere(1.0f, 16, 8, Vec3(kRho), Vec3(kLe)));
  RenderSettings settings = closed_sphere_settings(6);
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
