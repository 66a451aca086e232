// The noise estimate (film/noise_estimate.h): the film's snapshots, the estimator on frames of known variance,
// and its honesty on real renders: after 16, 64 and 256 frames each pass's estimated relMSE is within a factor of
// 1.5 of its true relMSE against a closed form or a long reference, with both samplers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

#include "core/rng.h"
#include "image/image_output.h"
#include "film/noise_estimate.h"
#include "film/noise_view.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "test_support.h"

namespace lueur {
namespace {

/// Issue 8's relMSE of `image` against `reference`: mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01).
double rel_mse(const Image& image, const Image& reference) {
  double sum = 0.0;
  for (size_t j = 0; j < image.rgb.size(); ++j) {
    const double d = static_cast<double>(image.rgb[j]) - reference.rgb[j];
    sum += d * d / (static_cast<double>(reference.rgb[j]) * reference.rgb[j] + 0.01);
  }
  return sum / static_cast<double>(image.rgb.size());
}

Image constant_image(int width, int height, float value) {
  return Image{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height), value)};
}

/// Renders `frames` frames, calling `at(film)` after each when given.
Film render(const TracedScene& traced, const CameraSpec& view, const RenderSettings& settings, int frames,
            const std::function<void(const Film&)>& at = {}) {
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  const Camera camera = make_camera(view, settings.width, settings.height);
  for (int f = 0; f < frames; ++f) {
    render_frame(traced, camera, settings, film, nullptr, pool);
    if (at) at(film);
  }
  return film;
}

/// Adds a frame to `film` whose every pixel channel of each layer in `layers` is a fresh `value(layer)`.
template <typename Value>
void add_test_frame(Film& film, std::initializer_list<Layer> layers, Value&& value) {
  if (film.unit == 0.0) film.unit = 0x1p-32;
  std::array<std::vector<Vec3>, kLayerCount> values;
  for (const Layer layer : layers) {
    std::vector<Vec3>& v = values[static_cast<size_t>(layer)];
    v.resize(film.pixel_count());
    for (Vec3& pixel : v)
      for (int c = 0; c < 3; ++c) pixel[c] = value(layer);
  }
  ASSERT_EQ(film.add_frame(values), 0u);
}

TEST(NoiseEstimate, FilmSnapshotsThePassSumsAtPowersOfTwo) {
  Film film;
  RenderSettings settings;
  settings.width = settings.height = 2;
  settings.enabled = {true, true, false, false};
  film.reset(settings);
  std::vector<float> at_four, at_eight;
  for (int f = 1; f <= 11; ++f) {
    add_test_frame(film, {Layer::kL1}, [&](Layer) { return static_cast<float>(f); });
    if (f == 4) at_four = film.sums[static_cast<size_t>(Layer::kL1)];
    if (f == 8) at_eight = film.sums[static_cast<size_t>(Layer::kL1)];
  }
  EXPECT_EQ(film.frames, 11u);
  EXPECT_EQ(film.checkpoints[0].frames, 8u);
  EXPECT_EQ(film.checkpoints[1].frames, 4u);
  EXPECT_EQ(film.checkpoints[2].frames, 2u);
  EXPECT_EQ(film.checkpoints[0].sums[static_cast<size_t>(Pass::kL1)], at_eight);
  EXPECT_EQ(film.checkpoints[1].sums[static_cast<size_t>(Pass::kL1)], at_four);
  EXPECT_TRUE(film.checkpoints[0].sums[static_cast<size_t>(Pass::kL2)].empty());  // not rendered
  film.reset(settings);
  EXPECT_EQ(film.checkpoints[0].frames, 0u);
  EXPECT_FALSE(estimate_pass_noise(film, Pass::kL1, SamplerKind::kIndependent).known);
}

TEST(NoiseEstimate, IndependentFramesOfKnownVarianceGiveThatVarianceOverTheFrames) {
  // Every pixel channel draws frames uniform in [0, 2) (mean 1, variance 1/3): the mean of F frames has variance
  // 1 / (3 F), and the relMSE against the true mean 1 is that over 1.01.
  Film film;
  RenderSettings settings;
  settings.width = settings.height = 64;
  settings.enabled = {false, true, false, false};
  film.reset(settings);
  Pcg32 rng(7, 1);
  for (int f = 1; f <= 100; ++f) {
    add_test_frame(film, {Layer::kL1}, [&](Layer) { return 2.0f * rng.next_float(); });
    if (f < 2) {
      EXPECT_FALSE(estimate_pass_noise(film, Pass::kL1, SamplerKind::kIndependent).known);
      continue;
    }
    const NoiseEstimate e = estimate_pass_noise(film, Pass::kL1, SamplerKind::kIndependent);
    ASSERT_TRUE(e.known);
    EXPECT_EQ(e.exponent, 1.0);
    const double expected = 1.0 / (3.0 * f) / 1.01;
    // 12288 pixel channels: the estimate's own spread is about 2%. The current mean stands in for the true one in
    // the denominator, and E[1 / m^2] exceeds 1 by about 3 Var(m) = 1 / f: a known excess, small after 16 frames.
    const double excess = 1.0 / f;
    EXPECT_GT(e.rel_mse / expected, 0.95) << f << " frames";
    EXPECT_LT(e.rel_mse / expected, 1.05 + 1.5 * excess) << f << " frames";
  }
  // The same frames read as Sobol frames: the fitted exponent stays near 1.
  const NoiseEstimate sobol = estimate_pass_noise(film, Pass::kL1, SamplerKind::kSobol);
  ASSERT_TRUE(sobol.known);
  EXPECT_LT(sobol.exponent, 1.1);
}

/// The squared half-differences D(N / 2^i) = V(N / 2^(i+1)) - V(N / 2^i) that a variance V gives, for i = 0, 1, 2.
template <typename Variance>
std::array<double, 3> differences_of(Variance&& variance, double newest) {
  std::array<double, 3> d{};
  for (int i = 0; i < 3; ++i) {
    const double n = newest / std::exp2(i);
    d[static_cast<size_t>(i)] = variance(n / 2.0) - variance(n);
  }
  return d;
}

TEST(NoiseEstimate, TheDecayFitRecoversAMixtureOfRatesAndFollowsASlowingFall) {
  // A mixture of the fitted rates is recovered exactly, now and further on.
  const auto mixture = [](double n) { return 0.3 / n + 5.0 / (n * n) + 40.0 / (n * n * n); };
  std::array<double, 3> d = differences_of(mixture, 64.0);
  VarianceDecay decay = fit_variance_decay(64, d.data(), 3);
  for (const double n : {64.0, 100.0, 1000.0}) EXPECT_NEAR(decay.at(n) / mixture(n), 1.0, 1e-9) << n;
  EXPECT_GT(decay.exponent_at(64.0), 1.0);
  EXPECT_LT(decay.exponent_at(64.0), 3.0);

  // Independent frames: the 1 / n rate alone, exponent 1.
  const auto independent = [](double n) { return 0.25 / n; };
  d = differences_of(independent, 32.0);
  decay = fit_variance_decay(32, d.data(), 3);
  EXPECT_NEAR(decay.at(32.0) / independent(32.0), 1.0, 1e-9);
  EXPECT_NEAR(decay.exponent_at(32.0), 1.0, 1e-9);

  // A pure power law between the rates (Owen-scrambled nets on a discontinuous 2D integrand fall as n^-1.5, say):
  // the mixture that matches its differences leans on 1 / n, which falls slower than the law beyond what they saw,
  // so it overstates the variance, by 20-40% for exponents between 1.2 and 2.5, never understates it.
  for (const double exponent : {1.2, 1.5, 1.8, 2.5}) {
    const auto power = [&](double n) { return std::pow(n, -exponent); };
    d = differences_of(power, 128.0);
    decay = fit_variance_decay(128, d.data(), 3);
    EXPECT_GT(decay.at(128.0) / power(128.0), 1.0) << exponent;
    EXPECT_LT(decay.at(128.0) / power(128.0), 1.4) << exponent;
  }

  // A fall that slows toward 1 / n (the Sobol sampler's, where a fast-converging part gives way to the padded
  // dimensions' interaction): one exponent fitted over the last halvings, (D(N/2) / D(N)) = 2^p, underestimates the
  // variance now by half; the mixture does not.
  const auto slowing = [](double n) { return 0.5 / n + 30.0 / (n * n * n); };
  d = differences_of(slowing, 16.0);
  decay = fit_variance_decay(16, d.data(), 3);
  EXPECT_NEAR(decay.at(16.0) / slowing(16.0), 1.0, 1e-6);
  const double p = std::log2(d[1] / d[0]);
  EXPECT_LT(d[0] / (std::exp2(p) - 1.0) / slowing(16.0), 0.5);

  // Only the newest difference: the cautious 1 / n. No difference at all: no noise.
  d = {1e-3, 0.0, 0.0};
  decay = fit_variance_decay(8, d.data(), 1);
  EXPECT_DOUBLE_EQ(decay.at(8.0), 1e-3);
  EXPECT_DOUBLE_EQ(decay.at(16.0), 0.5e-3);
  d = {0.0, 0.0, 0.0};
  EXPECT_EQ(fit_variance_decay(8, d.data(), 3).at(8.0), 0.0);
}

TEST(NoiseEstimate, TheRunningEstimateIsRemadeAtPowersOfTwoAndCarriedAlongItsDecayBetween) {
  Film film;
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.enabled = {true, true, false, false};
  film.reset(settings);
  Pcg32 rng(3, 9);
  RunningNoiseEstimate running, running_sobol;
  std::array<float, kPassCount> weights = kReportWeights;
  for (int f = 1; f <= 40; ++f) {
    add_test_frame(film, {Layer::kLe, Layer::kL1},
                   [&](Layer l) { return l == Layer::kLe ? 1.0f + rng.next_float() : 2.0f * rng.next_float(); });
    if (f == 20) weights[0] = 0.25f;  // a new weight remakes it at once
    const FilmNoise carried = running.update(film, settings.enabled, weights, SamplerKind::kIndependent);
    // The Sobol sampler's fitted decay carries its estimate the same way.
    const FilmNoise carried_sobol = running_sobol.update(film, settings.enabled, weights, SamplerKind::kSobol);
    const NoiseEstimate full_sobol = estimate_image_noise(film, settings.enabled, weights, SamplerKind::kSobol);
    ASSERT_EQ(carried_sobol.image.known, full_sobol.known) << f;
    if (full_sobol.known) {
      if ((f & (f - 1)) == 0 || f == 20)
        EXPECT_EQ(carried_sobol.image.rel_mse, full_sobol.rel_mse) << f;
      else
        EXPECT_NEAR(carried_sobol.image.rel_mse / full_sobol.rel_mse, 1.0, 0.05) << f;
    }
    const NoiseEstimate full = estimate_image_noise(film, settings.enabled, weights, SamplerKind::kIndependent);
    ASSERT_EQ(carried.image.known, full.known) << f;
    if (!full.known) continue;
    if ((f & (f - 1)) == 0 || f == 20)
      EXPECT_EQ(carried.image.rel_mse, full.rel_mse) << f;
    else
      EXPECT_NEAR(carried.image.rel_mse / full.rel_mse, 1.0, 0.05) << f;
    EXPECT_EQ(carried.passes[static_cast<size_t>(Pass::kL1)].known, true);
    EXPECT_FALSE(carried.passes[static_cast<size_t>(Pass::kL2)].known);  // not rendered
  }
}

/// Checks the estimate of every enabled pass but `unchecked`, and of the image those passes combine to with the
/// report's weights, after 16, 64 and 256 frames against the true relMSE against `reference(pass)` (and their weighted
/// sum): within a factor of 1.5 either way. Both below `floor` (a relative error of 0.03%: the closed sphere's Le,
/// exact but for rays that slip between triangles) counts as agreement. Every figure is printed.
void expect_honest(const TracedScene& traced, const CameraSpec& view, const RenderSettings& settings,
                   const std::function<Image(Pass)>& reference, const std::string& name,
                   std::optional<Pass> unchecked = std::nullopt, double floor = 1e-7) {
  std::array<bool, kPassCount> image_passes = settings.enabled;
  if (unchecked) image_passes[static_cast<size_t>(*unchecked)] = false;
  Image image_reference{settings.width, settings.height,
                        std::vector<float>(3 * static_cast<size_t>(settings.width * settings.height), 0.0f)};
  for (int p = 0; p < kPassCount; ++p) {
    if (!image_passes[static_cast<size_t>(p)]) continue;
    const Image pass = reference(static_cast<Pass>(p));
    for (size_t j = 0; j < pass.rgb.size(); ++j)
      image_reference.rgb[j] += kReportWeights[static_cast<size_t>(p)] * pass.rgb[j];
  }
  render(traced, view, settings, 256, [&](const Film& film) {
    if (film.frames != 16 && film.frames != 64 && film.frames != 256) return;
    const auto check = [&](const std::string& what_of, const NoiseEstimate& e, double truth, bool checked) {
      ASSERT_TRUE(e.known);
      const std::string what = name + ", " + what_of + " after " + std::to_string(film.frames) + " frames: estimated " +
                               std::to_string(e.rel_mse) + ", true " + std::to_string(truth) + ", exponent " +
                               std::to_string(e.exponent);
      std::printf("%s\n", what.c_str());
      if ((truth < floor && e.rel_mse < floor) || !checked) return;
      EXPECT_GT(e.rel_mse, truth / 1.5) << what;
      EXPECT_LT(e.rel_mse, truth * 1.5) << what;
    };
    for (int p = 0; p < kPassCount; ++p) {
      const Pass pass = static_cast<Pass>(p);
      if (!settings.pass_enabled(pass)) continue;
      check(std::string(kPassNames[static_cast<size_t>(p)]), estimate_pass_noise(film, pass, settings.sampler),
            rel_mse(pass_average(film, pass), reference(pass)), pass != unchecked);
    }
    check("the image", estimate_image_noise(film, image_passes, kReportWeights, settings.sampler),
          rel_mse(combine_passes(film, image_passes, kReportWeights), image_reference), true);
  });
}

/// Checks the estimate in a closed scene whose every triangle emits Le with albedo rho: Le, L1 = rho Le and
/// L2 = rho^2 Le at every pixel, so the reference is exact.
void expect_honest_in_closed_emitting_scene(Scene scene, float rho, float le) {
  const auto traced = prepare_scene(std::move(scene));
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.enabled = {true, true, true, false};
  settings.blinn_k = 1.0f;
  settings.reuse = ReuseMode::kOff;
  settings.l1_rays = 4;
  settings.l2_rays = 4;
  const CameraSpec view{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f};
  const auto reference = [&](Pass pass) {
    const float value = pass == Pass::kLe ? le : pass == Pass::kL1 ? rho * le : rho * rho * le;
    return constant_image(settings.width, settings.height, value);
  };
  for (const SamplerKind sampler : {SamplerKind::kIndependent, SamplerKind::kSobol}) {
    settings.sampler = sampler;
    expect_honest(*traced, view, settings, reference, std::string(kSamplerKindNames[static_cast<size_t>(sampler)]));
  }
}

TEST(NoiseEstimate, IsWithinOneAndAHalfOfTheTrueErrorInTheClosedSphere) {
  // A coarse sphere, 24 x 12 triangles. Where two of them meet at an angle, a point by the edge has the next one
  // close to its plane, and area sampling's cos cos / d^2 grows as 1 / d^2 there: with area sampling alone one
  // sample in one pixel outweighed the rest of the image, and only 128 x 64 triangles made that tail negligible.
  // Sampled by solid angle near their plane, as L1 now does, the coarse faces are as well behaved.
  expect_honest_in_closed_emitting_scene(test::make_closed_emitting_sphere(1.0f, 24, 12, Vec3(0.6f), Vec3(2.0f)), 0.6f,
                                         2.0f);
}

TEST(NoiseEstimate, IsWithinOneAndAHalfOfTheTrueErrorInTheClosedBox) {
  // Six emitting walls meeting at right angles. By an edge, area sampling's weight for the next wall grows as
  // 1 / distance^2, an estimator of infinite variance that no estimate of the variance can follow (the estimate was
  // 0.1x-0.5x the true error); L1 samples such a nearby emitter by solid angle, and the estimate holds up to the
  // corners.
  expect_honest_in_closed_emitting_scene(test::make_closed_emitting_box(1.0f, Vec3(0.6f), Vec3(2.0f)), 0.6f, 2.0f);
}

TEST(NoiseEstimate, IsWithinOneAndAHalfOfTheTrueErrorOnTheDefaultScene) {
  // The reference: the same settings over 8 times the frames, with another seed (its own error adds at most an
  // eighth to the true error after 256 frames). Four rays of each kind per frame keep the frames cheap, so that the
  // image can be large enough for its relMSE not to hang on a handful of pixels.
  const auto traced = prepare_scene(make_default_scene());
  RenderSettings settings;
  settings.width = settings.height = 48;
  settings.enabled = {true, true, true, true};
  settings.l1_rays = settings.l2_rays = settings.ao_rays = 4;
  for (const SamplerKind sampler : {SamplerKind::kSobol, SamplerKind::kIndependent}) {
    settings.sampler = sampler;
    RenderSettings long_run = settings;
    long_run.seed = 99;
    const Film reference = render(*traced, default_scene_camera(), long_run, 2048);
    // Le is printed, not checked: NOT MET. Its error lives on the few pixels that cut a light's edge (the wall
    // lamp is small and bright), where a pixel sees the light in a few percent of its camera rays. The true error
    // itself is a lottery there: over 16 seeds at 48 x 48 it spread from 0.25x to 2.8x its mean after 16 frames,
    // and at 512 x 512 two renders in twelve had 10-30x the others' from one camera ray that hit the lamp. No
    // estimate of the expected error follows one render's draw (BENCHMARKS.md).
    // Sobol frames over three seeds: a fit of how fast the variance falls could pass one seed by chance.
    for (const uint64_t seed :
         sampler == SamplerKind::kSobol ? std::vector<uint64_t>{0, 1, 2} : std::vector<uint64_t>{0}) {
      settings.seed = seed;
      expect_honest(
          *traced, default_scene_camera(), settings, [&](Pass pass) { return pass_average(reference, pass); },
          std::string(kSamplerKindNames[static_cast<size_t>(sampler)]) + " seed " + std::to_string(seed), Pass::kLe);
    }
  }
}

TEST(NoiseEstimate, TheHeadlessSummaryEndsWithTheImagesEstimateAndATargetStopsTheRender) {
  const std::string dir = test::make_temp_dir("noise_summary");
  const test::CommandResult run = test::run_lueur("--headless --out " + dir + "/a.pfm --size 48x48 --frames 8");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (const char* line : {"le pass: estimated relMSE ", "l1 pass: estimated relMSE ", "l2 pass: estimated relMSE ",
                           "image: estimated relMSE "})
    EXPECT_NE(run.output.find(line), std::string::npos) << line << " missing from:\n" << run.output;
  // The image's figure comes last, as a plain number.
  const size_t last = run.output.rfind("estimated relMSE ");
  EXPECT_EQ(run.output.rfind("image: estimated relMSE "), last - 7);
  const double figure = std::stod(run.output.substr(last + 17));
  EXPECT_GT(figure, 0.0);
  EXPECT_LT(figure, 0.1);

  // A target between the estimate after 8 frames and after 4096 stops the render early, and says so.
  char target[32];
  std::snprintf(target, sizeof target, "%g", figure * 0.5);
  const test::CommandResult stopped = test::run_lueur("--headless --out " + dir +
                                                      "/b.pfm --size 48x48 --frames 4096 "
                                                      "--target-noise " +
                                                      std::string(target));
  ASSERT_EQ(stopped.exit_code, 0) << stopped.output;
  const size_t said = stopped.output.find("target noise " + std::string(target) + " reached after ");
  ASSERT_NE(said, std::string::npos) << stopped.output;
  const int frames = std::stoi(stopped.output.substr(said + 28 + std::string(target).size()));
  EXPECT_GT(frames, 8);
  EXPECT_LT(frames, 4096);
  const size_t final_figure = stopped.output.rfind("estimated relMSE ");
  EXPECT_LT(std::stod(stopped.output.substr(final_figure + 17)), figure * 0.5);

  // Unreachable within the cap: said too.
  const test::CommandResult capped =
      test::run_lueur("--headless --out " + dir + "/c.pfm --size 32x32 --frames 4 --target-noise 1e-12");
  ASSERT_EQ(capped.exit_code, 0) << capped.output;
  EXPECT_NE(capped.output.find("target noise 1e-12 not reached in 4 frames"), std::string::npos) << capped.output;
}

TEST(NoiseEstimate, TheNoiseViewShowsEachPixelsErrorInFalseColourWithItsScale) {
  const std::string dir = test::make_temp_dir("noise_view");
  const test::CommandResult run =
      test::run_lueur("--headless --out " + dir + "/noise.pfm --size 96x96 --frames 16 --view noise --exposure 3");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Image view = decode_pfm(test::read_file(dir + "/noise.pfm"));
  ASSERT_EQ(view.width, 96);
  // Every pixel above the scale strip is a colour of the scale (linear, not exposed: --exposure does not apply),
  // and the map is not one colour.
  const auto linear = [](const Vec3& srgb) {
    const auto one = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
    return Vec3(one(srgb.r), one(srgb.g), one(srgb.b));
  };
  float lowest = 1e9f, highest = -1e9f;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < view.width; ++x) {
      const Vec3 c = view.at(x, y);
      float best = 1e9f, where = 0.0f;
      for (int k = 0; k <= 300; ++k) {
        const float e = kNoiseViewLowest * std::pow(kNoiseViewHighest / kNoiseViewLowest, k / 300.0f);
        const float d = glm::length(c - linear(noise_scale_colour(e)));
        if (d < best) {
          best = d;
          where = static_cast<float>(k);
        }
      }
      ASSERT_LT(best, 0.02f) << "pixel " << x << ", " << y;
      lowest = std::min(lowest, where);
      highest = std::max(highest, where);
    }
  EXPECT_GT(highest - lowest, 30.0f);
  // The scale's bar along the bottom: its left end is the quiet end's colour, its right end the noisy end's.
  bool quiet = false, noisy = false;
  for (int y = view.height - 12; y < view.height; ++y) {
    quiet = quiet || glm::length(view.at(6, y) - linear(noise_scale_colour(kNoiseViewLowest))) < 0.02f;
    noisy = noisy || glm::length(view.at(view.width - 12, y) - linear(noise_scale_colour(kNoiseViewHighest))) < 0.05f;
  }
  EXPECT_TRUE(quiet);
  EXPECT_TRUE(noisy);
}

}  // namespace
}  // namespace lueur
