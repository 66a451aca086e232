// The renderer as a whole: determinism across thread counts, strategies agreeing in expectation, the embedded
// default scene against its OBJ copy in assets/, and the image encoders.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/atomic_file.h"
#include "image/image_output.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

Film render_default(const TracedScene& traced, RenderSettings settings, int frames, int threads) {
  Film film;
  film.reset(settings);
  ThreadPool pool(threads);
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  for (int f = 0; f < frames; ++f) render_frame(traced, camera, settings, film, nullptr, pool);
  return film;
}

std::shared_ptr<const TracedScene> default_traced() {
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  return prepare_scene(std::move(scene));
}

/// Bit-for-bit equality (memcmp of an empty vector's null data() would be undefined behaviour).
bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(Render, BitIdenticalForAnyThreadCount) {
  const auto traced = default_traced();
  RenderSettings settings;
  settings.width = 61;  // not a multiple of the tile size
  settings.height = 47;
  settings.l1_rays = 4;
  settings.seed = 3;
  const Film one = render_default(*traced, settings, 3, 1);
  const Film two = render_default(*traced, settings, 3, 2);
  const Film five = render_default(*traced, settings, 3, 5);
  for (int p = 0; p < kPassCount; ++p) {
    const auto& a = one.sums[static_cast<size_t>(p)];
    ASSERT_EQ(a.size(), two.sums[static_cast<size_t>(p)].size());
    EXPECT_TRUE(same_bytes(a, two.sums[static_cast<size_t>(p)])) << "pass " << p;
    EXPECT_TRUE(same_bytes(a, five.sums[static_cast<size_t>(p)])) << "pass " << p;
  }
  // A different seed gives a different image: the seed really reaches the random streams.
  settings.seed = 4;
  const Film other = render_default(*traced, settings, 3, 2);
  EXPECT_FALSE(same_bytes(one.sums[1], other.sums[1]));
}

/// Per block of kBlock x kBlock pixels, L1's mean over `frames` frames and its standard error, from the spread of
/// the frames' own block means.
struct BlockMeans {
  std::vector<double> mean, standard_error;
};
constexpr int kBlock = 8;

BlockMeans l1_block_means(const TracedScene& traced, const RenderSettings& settings, int frames) {
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  const int blocks_x = settings.width / kBlock, blocks = blocks_x * (settings.height / kBlock);
  std::vector<double> sum(static_cast<size_t>(blocks), 0.0), sum2(sum);
  std::vector<float> before(film.sums[static_cast<size_t>(Layer::kL1)]);
  for (int f = 0; f < frames; ++f) {
    render_frame(traced, camera, settings, film, nullptr, pool);
    const std::vector<float>& after = film.sums[static_cast<size_t>(Layer::kL1)];
    std::vector<double> frame(static_cast<size_t>(blocks), 0.0);
    for (int y = 0; y < settings.height; ++y)
      for (int x = 0; x < settings.width; ++x) {
        const size_t i = 3 * static_cast<size_t>(y * settings.width + x);
        const double luminance = (after[i] - before[i]) + (after[i + 1] - before[i + 1]) + (after[i + 2] - before[i + 2]);
        frame[static_cast<size_t>((y / kBlock) * blocks_x + x / kBlock)] += luminance / (kBlock * kBlock);
      }
    before = after;
    for (size_t b = 0; b < frame.size(); ++b) {
      sum[b] += frame[b];
      sum2[b] += frame[b] * frame[b];
    }
  }
  BlockMeans result;
  for (size_t b = 0; b < sum.size(); ++b) {
    const double mean = sum[b] / frames, variance = std::max(0.0, sum2[b] / frames - mean * mean);
    result.mean.push_back(mean);
    result.standard_error.push_back(std::sqrt(variance / (frames - 1)));
  }
  return result;
}

TEST(Render, EveryLightStrategyHasTheSameExpectedImage) {
  // Compared block by block, so that a bias in one region cannot hide behind another of the other sign, as it could
  // in the whole image's mean.
  const auto traced = default_traced();
  RenderSettings settings;
  settings.width = settings.height = 32;
  settings.l1_rays = 16;
  settings.enabled = {false, true, false, false};
  settings.lights = LightStrategy::kAll;
  const BlockMeans all = l1_block_means(*traced, settings, 16);
  int lit_blocks = 0;
  for (const double m : all.mean) lit_blocks += m > 0.01 ? 1 : 0;
  EXPECT_GE(lit_blocks, 12);
  for (const LightStrategy s :
       {LightStrategy::kUniform, LightStrategy::kArea, LightStrategy::kPower, LightStrategy::kImportance}) {
    settings.lights = s;
    const BlockMeans other = l1_block_means(*traced, settings, 64);
    for (size_t b = 0; b < all.mean.size(); ++b) {
      const double se = std::hypot(all.standard_error[b], other.standard_error[b]);
      EXPECT_NEAR(other.mean[b], all.mean[b], 5.0 * se + 1e-4 * all.mean[b])
          << kLightStrategyNames[static_cast<size_t>(s)] << ", block " << b;
    }
  }
}

// More camera rays for Le change Le alone: the layers the first ray shades (L1, L2 and the reuse layers) stay
// byte for byte the same. And Le converges faster per frame: against a long render, 8 frames with 4 Le rays have
// less error than 8 frames with one, and about as little as 32 frames with one (the same number of camera rays).
TEST(Render, ExtraLeRaysChangeOnlyLeAndAntiAliasTheEmitters) {
  const auto traced = default_traced();
  RenderSettings settings;
  settings.width = settings.height = 48;
  settings.l1_rays = settings.l2_rays = 2;
  settings.le_rays = 1;
  const Film one = render_default(*traced, settings, 2, 2);
  settings.le_rays = 4;
  const Film four = render_default(*traced, settings, 2, 2);
  for (const Layer layer : {Layer::kL1, Layer::kL2, Layer::kL2Reused, Layer::kL2Recomputed, Layer::kReuseFraction})
    EXPECT_TRUE(same_bytes(one.sums[static_cast<size_t>(layer)], four.sums[static_cast<size_t>(layer)]))
        << kLayerNames[static_cast<size_t>(layer)];
  EXPECT_FALSE(same_bytes(one.sums[0], four.sums[0]));

  // Le alone: emission seen directly, its error concentrated on the lights' edges.
  RenderSettings le_only = settings;
  le_only.enabled = {true, false, false, false};
  auto le_error = [&](int le_rays, int frames, const Image& reference) {
    le_only.le_rays = le_rays;
    const Image image = layer_average(render_default(*traced, le_only, frames, 2), Layer::kLe);
    double sum = 0.0;
    for (size_t i = 0; i < image.rgb.size(); ++i) sum += std::pow(image.rgb[i] - reference.rgb[i], 2.0);
    return sum / static_cast<double>(image.rgb.size());
  };
  le_only.le_rays = 16;
  le_only.seed = 99;
  const Image reference = layer_average(render_default(*traced, le_only, 64, 2), Layer::kLe);
  le_only.seed = 0;
  const double one_ray = le_error(1, 8, reference), four_rays = le_error(4, 8, reference),
               one_ray_long = le_error(1, 32, reference);
  EXPECT_GT(one_ray, 0.0);
  EXPECT_LT(four_rays, 0.5 * one_ray) << "one ray " << one_ray << ", four " << four_rays;
  EXPECT_LT(four_rays, 2.0 * one_ray_long) << "32 frames of one ray " << one_ray_long << ", 8 of four " << four_rays;
}

TEST(DefaultScene, HasTheBoxTheAppleAndTwoVeryDifferentLights) {
  const Scene scene = make_default_scene();
  size_t apple = 0;
  for (const Triangle& t : scene.triangles) apple += scene.materials[t.material].name.rfind("apple", 0) == 0;
  EXPECT_GE(apple, 200u);
  EXPECT_LE(apple, 800u);
  float smallest = kInfinity, largest = 0.0f;
  for (const uint32_t e : scene.emitters) {
    smallest = std::min(smallest, scene.area(e));
    largest = std::max(largest, scene.area(e));
  }
  EXPECT_GE(scene.emitters.size(), 64u);
  EXPECT_GT(largest / smallest, 50.0f);
}

TEST(DefaultScene, AgreesWithItsObjCopyInAssets) {
  const Scene embedded = make_default_scene();
  LoadOptions options;
  options.smooth_normals = false;
  const LoadedScene loaded = load_obj(std::string(LUEUR_SOURCE_DIR) + "/assets/cornell-apple.obj", options);
  const Scene& file = loaded.scene;
  ASSERT_EQ(file.triangles.size(), embedded.triangles.size());
  ASSERT_EQ(file.emitters.size(), embedded.emitters.size());
  for (size_t t = 0; t < embedded.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(file.positions[file.triangles[t].v[k]], embedded.positions[embedded.triangles[t].v[k]])
          << "triangle " << t;
    const Material& a = file.materials[file.triangles[t].material];
    const Material& b = embedded.materials[embedded.triangles[t].material];
    ASSERT_EQ(a.name, b.name);
    ASSERT_EQ(a.kd, b.kd);
    ASSERT_EQ(a.ks, b.ks);
    ASSERT_EQ(a.ns, b.ns);
    ASSERT_EQ(a.ke, b.ke);
  }
}

TEST(Render, NonFiniteSamplesAreDroppedAndCounted) {
  // An emitter of infinite radiance (which the loader never lets through) seen straight on: every pixel's Le
  // sample is infinite, and the film must stay finite anyway.
  const float inf = std::numeric_limits<float>::infinity();
  const auto traced = prepare_scene(test::make_rect_light_over_floor(4.0f, 4.0f, 1.0f, Vec3(0.5f), Vec3(inf)));
  RenderSettings settings;
  settings.width = settings.height = 8;
  settings.enabled = {true, true, true, true};
  settings.l1_rays = settings.l2_rays = settings.ao_rays = 1;
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  // From the floor looking up at the light's emitting side.
  const Camera camera = make_camera({Vec3(0.0f, 0.2f, 0.0f), Vec3(0.0f, 1.0f, 0.01f), Vec3(0, 0, 1), 60.0f}, 8, 8);
  uint64_t dropped = 0;
  for (int f = 0; f < 2; ++f) dropped += render_frame(*traced, camera, settings, film, nullptr, pool).dropped_samples;
  EXPECT_GE(dropped, 2u * 64u) << "every pixel sees the light";
  for (const auto& sums : film.sums)
    for (const float v : sums) ASSERT_TRUE(std::isfinite(v));
  EXPECT_EQ(film.frames, 2u);
}

Image make_test_image(int w, int h) {
  Image image{w, h, std::vector<float>(static_cast<size_t>(3 * w * h))};
  for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<float>(i % 97) * 0.03125f - 0.5f;
  return image;
}

TEST(ImageOutput, PfmRoundTripsExactly) {
  const Image image = make_test_image(7, 5);
  const Image back = decode_pfm(encode_pfm(image));
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, image.rgb);
}

TEST(ImageOutput, PngCarriesItsSettingsAndIsAValidPng) {
  const Image image = make_test_image(9, 4);
  const std::string png = encode_png(image, DisplaySettings{}, "lueur --lights area");
  ASSERT_GT(png.size(), 50u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(png.find(std::string("tEXtlueur\0lueur --lights area", 29)), std::string::npos);
  EXPECT_NE(png.find("IDAT"), std::string::npos);
  EXPECT_GT(png.find("IDAT"), png.find("tEXt"));
}

TEST(ImageOutput, ExrHasOneLayerPerPass) {
  const Image image = make_test_image(8, 8);
  const std::string exr = encode_exr(image, {{"l1", image}, {"le", image}}, "settings");
  EXPECT_EQ(static_cast<unsigned char>(exr[0]), 0x76);  // OpenEXR magic 76 2f 31 01
  for (const char* name : {"l1.R", "l1.G", "le.B", "settings"}) EXPECT_NE(exr.find(name), std::string::npos) << name;
}

TEST(ImageOutput, UnwritablePathLeavesNothingBehind) {
  const std::string dir = test::make_temp_dir("unwritable");
  const Image image = make_test_image(4, 4);
  EXPECT_THROW(write_image(dir + "/missing/sub/x.png", image, {}, {}), IoError);
  EXPECT_THROW(write_image(dir + "/x.bmp", image, {}, {}), IoError);
  EXPECT_FALSE(test::file_exists(dir + "/x.bmp"));
  write_image(dir + "/ok.pfm", image, {}, {});
  EXPECT_EQ(decode_pfm(test::read_file(dir + "/ok.pfm")).rgb, image.rgb);
}

TEST(Tonemap, QuantisesLikeTheDisplay) {
  EXPECT_EQ(quantize_unorm8(display_transform(Vec3(0.0f), {}).r), 0);
  EXPECT_EQ(quantize_unorm8(display_transform(Vec3(1.0f), {}).r), 255);
  EXPECT_EQ(quantize_unorm8(display_transform(Vec3(0.5f), {}).r), 188);                       // sRGB(0.5) = 0.7354
  EXPECT_EQ(quantize_unorm8(display_transform(Vec3(0.25f), {1.0f, ToneMap::kNone}).r), 188);  // one stop up
  EXPECT_NEAR(display_transform(Vec3(1.0f), {0.0f, ToneMap::kReinhard}).r, linear_to_srgb(0.5f), 1e-6f);
  EXPECT_EQ(quantize_unorm8(std::nanf("")), 0);
}

}  // namespace
}  // namespace lueur
