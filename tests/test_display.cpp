// The GL display path against its CPU reference: the same film through the display shaders in an EGL and an
// OSMesa context (Mesa's llvmpipe, no GPU needed) must equal the CPU tone mapping within one level per channel,
// for every tone map, exposure, weights and single-layer views.
#include <gtest/gtest.h>

#include <random>

#include "display/window_layout.h"
#include "film/noise_view.h"
#include "image/image_output.h"
#include "test_support.h"
#include "ui/headless_screenshot.h"
#include "ui/pixel_inspector.h"

namespace lueur {
namespace {

/// A film with sums spread over five orders of magnitude, so every part of the tone curves is exercised.
Film random_film(int width, int height, uint64_t frames, uint32_t seed) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.enabled = {true, true, true, true};
  Film film;
  film.reset(settings);
  film.frames = frames;  // only the float sums are set: what the display reads
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> exponent(-4.0f, 1.5f);
  for (auto& sum : film.sums)
    for (float& v : sum) v = static_cast<float>(frames) * std::pow(10.0f, exponent(random));
  return film;
}

std::vector<uint8_t> cpu_reference(const Film& film, const Settings& view) {
  if (view.show_noise)  // false colours: never exposed or tone mapped
    return tonemap_to_rgb8(noise_view_image(film, view.render.enabled, view.weights, view.render.sampler),
                           DisplaySettings{});
  return tonemap_to_rgb8(shown_image(film, view.render.enabled, view.weights, view.layer), view.display);
}

/// A film accumulated frame by frame (so that it holds the noise estimate's snapshots), of random frames whose
/// noise varies across the image.
Film noisy_film(int width, int height, int frames) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  Film film;
  film.reset(settings);
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  film.unit = 0x1p-32;
  std::array<std::vector<Vec3>, kLayerCount> values;
  for (int f = 0; f < frames; ++f) {
    for (size_t l = 0; l < kLayerCount; ++l) {
      if (!film.has(static_cast<Layer>(l))) continue;
      values[l].resize(film.pixel_count());
      for (size_t i = 0; i < 3 * film.pixel_count(); ++i)
        values[l][i / 3][static_cast<int>(i % 3)] = 0.5f + static_cast<float>(i % 97) / 97.0f * (unit(random) - 0.5f);
    }
    film.add_frame(values);
  }
  return film;
}

/// Largest difference per channel between two RGB8 images of the same size.
int max_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  int worst = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  return worst;
}

class GlDisplay : public ::testing::TestWithParam<HeadlessGl> {};

TEST_P(GlDisplay, EqualsTheCpuToneMappingWithinOneLevel) {
  const Film film = random_film(67, 41, 13, 5);  // odd sizes catch row-order and alignment mistakes
  std::vector<Settings> views;
  for (int t = 0; t < 3; ++t)
    for (float exposure : {-2.0f, 0.0f, 1.5f}) {
      Settings v;
      v.display.tonemap = static_cast<ToneMap>(t);
      v.display.exposure = exposure;
      views.push_back(v);
    }
  Settings weighted;
  weighted.render.enabled = {true, false, true, true};
  weighted.weights = {0.3f, 5.0f, 1.7f, 0.25f};
  views.push_back(weighted);
  Settings single;
  single.layer = Layer::kReuseFraction;
  single.display.tonemap = ToneMap::kReinhard;
  views.push_back(single);

  for (const Settings& view : views) {
    Screenshot shot;
    try {
      shot = render_headless_screenshot(GetParam(), film, view);
    } catch (const std::runtime_error& e) {
      FAIL() << "no " << kHeadlessGlNames[static_cast<size_t>(GetParam())] << " context: " << e.what();
    }
    ASSERT_EQ(shot.width, film.width);
    ASSERT_EQ(shot.height, film.height);
    const std::vector<uint8_t> cpu = cpu_reference(film, view);
    EXPECT_LE(max_difference(shot.rgb, cpu), 1)
        << shot.context << ", tone map " << kToneMapNames[static_cast<size_t>(view.display.tonemap)] << ", exposure "
        << view.display.exposure;
  }
}

TEST_P(GlDisplay, ShowsTheNoiseViewAsTheCpuDrawsItWithoutExposureOrToneMap) {
  const Film film = noisy_film(131, 83, 16);
  Settings view;
  view.show_noise = true;
  view.display.exposure = 2.0f;  // ignored by the noise view
  view.display.tonemap = ToneMap::kAces;
  Screenshot shot;
  try {
    shot = render_headless_screenshot(GetParam(), film, view);
  } catch (const std::runtime_error& e) {
    FAIL() << "no " << kHeadlessGlNames[static_cast<size_t>(GetParam())] << " context: " << e.what();
  }
  const std::vector<uint8_t> cpu = cpu_reference(film, view);
  EXPECT_LE(max_difference(shot.rgb, cpu), 1) << shot.context;
  // And it is a map, not one colour: the film's noise grows across each row.
  int spread = 0;
  for (size_t i = 0; i < cpu.size(); ++i) spread = std::max(spread, std::abs(int(cpu[i]) - int(cpu[0])));
  EXPECT_GT(spread, 64);
}

TEST_P(GlDisplay, AnEmptyFilmIsBlack) {
  Film film = random_film(8, 8, 0, 1);
  const Screenshot shot = render_headless_screenshot(GetParam(), film, Settings{});
  for (uint8_t v : shot.rgb) ASSERT_EQ(v, 0);
}

INSTANTIATE_TEST_SUITE_P(Contexts, GlDisplay, ::testing::Values(HeadlessGl::kEgl, HeadlessGl::kOsmesa),
                         [](const ::testing::TestParamInfo<HeadlessGl>& param_info) {
                           return std::string(kHeadlessGlNames[static_cast<size_t>(param_info.param)]);
                         });

TEST(PixelInspector, NamesEveryLayerAndEachPassAsItsViewIsNamed) {
  // Its labels were once a table one entry short of the layers: the store modes' cell layer read past it, and
  // pointing at the image crashed the window.
  for (int l = 0; l < kLayerCount; ++l) {
    const char* label = pixel_layer_label(static_cast<Layer>(l));
    ASSERT_NE(label, nullptr) << kLayerNames[static_cast<size_t>(l)];
    if (l < kPassCount) {
      std::string lower(label);
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      EXPECT_EQ(lower, kLayerNames[static_cast<size_t>(l)]);
    }
  }
}

TEST(WindowLayout, ThePanelTakesTheLeftColumnAndTheImageTheRest) {
  const WindowLayout layout = lay_out_window(852, 512, 852, 512, 340.0);
  EXPECT_FALSE(layout.panel_over_image);
  EXPECT_EQ(layout.image.x, 340.0);
  EXPECT_EQ(layout.image.width, 512.0);
  EXPECT_EQ(layout.image.height, 512.0);
  EXPECT_EQ(layout.image_pixels.x, 340);
  EXPECT_EQ(layout.image_pixels.width, 512);
  EXPECT_EQ(layout.image_pixels.height, 512);
  EXPECT_FALSE(layout.image.contains(339.5, 10.0)) << "over the panel";
  EXPECT_TRUE(layout.image.contains(340.0, 10.0));
  EXPECT_FALSE(layout.image.contains(852.0, 10.0));
}

TEST(WindowLayout, AHighDpiFramebufferScalesTheColumn) {
  const WindowLayout layout = lay_out_window(852, 512, 1704, 1024, 340.0);
  EXPECT_EQ(layout.image.x, 340.0);  // window coordinates, as the mouse reports them
  EXPECT_EQ(layout.image_pixels.x, 680);
  EXPECT_EQ(layout.image_pixels.width, 1024);
  EXPECT_EQ(layout.image_pixels.height, 1024);
}

TEST(WindowLayout, ANarrowWindowOrAHiddenPanelGivesTheImageTheWholeWindow) {
  for (const double panel : {340.0, 0.0}) {
    const WindowLayout narrow = lay_out_window(400, 300, 400, 300, panel);
    EXPECT_EQ(narrow.panel_over_image, panel > 0.0);
    EXPECT_EQ(narrow.image.x, 0.0);
    EXPECT_EQ(narrow.image_pixels.x, 0);
    EXPECT_EQ(narrow.image_pixels.width, 400);
  }
  const WindowLayout hidden = lay_out_window(852, 512, 852, 512, 0.0);
  EXPECT_FALSE(hidden.panel_over_image);
  EXPECT_EQ(hidden.image_pixels.width, 852);
  const WindowLayout empty = lay_out_window(0, 0, 0, 0, 340.0);  // minimised
  EXPECT_EQ(empty.image_pixels.width, 0);
  EXPECT_EQ(empty.image_pixels.height, 0);
}

TEST(WindowLayout, AWindowSizedForAnImageShowsItAtThatSize) {
  for (const double panel : {0.0, 240.0, 340.0, 511.5})
    for (int width = 1; width <= 2000; width += 37) {
      const int window_width = window_width_for_image(width, panel);
      const WindowLayout layout = lay_out_window(window_width, 100, window_width, 100, panel);
      EXPECT_EQ(layout.image_pixels.width, width) << "panel " << panel << ", window " << window_width;
      EXPECT_EQ(layout.image_pixels.x + layout.image_pixels.width, window_width);
    }
}

TEST(GlDisplay, ThePanelSitsBesideTheImageWhichItLeavesAsItWas) {
  const Film film = random_film(480, 420, 3, 9);
  PanelModel panel;
  panel.scene_name = "random film";
  const Screenshot plain = render_headless_screenshot(HeadlessGl::kEgl, film, Settings{});
  const Screenshot with_ui = render_headless_screenshot(HeadlessGl::kEgl, film, Settings{}, &panel);
  const int panel_width = static_cast<int>(kPanelWidth);
  ASSERT_EQ(with_ui.width, film.width + panel_width) << "the screenshot is as wide as the window: panel and image";
  ASSERT_EQ(with_ui.height, film.height);
  const auto at = [](const Screenshot& shot, int x, int y, int c) {
    return shot.rgb[3 * (static_cast<size_t>(y) * static_cast<size_t>(shot.width) + static_cast<size_t>(x)) + c];
  };
  int image_differs = 0, panel_lit = 0;
  for (int y = 0; y < film.height; ++y)
    for (int c = 0; c < 3; ++c) {
      for (int x = 0; x < film.width; ++x) image_differs += at(plain, x, y, c) != at(with_ui, panel_width + x, y, c);
      for (int x = 0; x < panel_width; ++x) panel_lit += at(with_ui, x, y, c) != 0;
    }
  EXPECT_EQ(image_differs, 0) << "the image beside the panel is the plain screenshot, pixel for pixel";
  EXPECT_GT(panel_lit, 3 * panel_width * film.height / 2) << "the panel's column is drawn (opaque, not black)";
}

TEST(GlDisplay, HeadlessScreenshotsThroughTheCommandLine) {
  const std::string dir = test::make_temp_dir("gl-cli");
  const auto run = [&](const std::string& gl, const std::string& out) {
    return test::run_lueur("--headless --size 48x40 --frames 2 --l1-rays 2 --l2-rays 2 --gl " + gl + " --out " + dir +
                           "/" + out);
  };
  for (const char* gl : {"none", "egl", "osmesa", "auto"}) {
    const test::CommandResult r = run(gl, std::string(gl) + ".png");
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  // A screenshot is a PNG; linear formats and unknown contexts are refused before rendering.
  const test::CommandResult bad = run("egl", "shot.pfm");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--out must be a .png"), std::string::npos) << bad.output;
  const test::CommandResult bad_gl = run("vulkan", "x.png");
  EXPECT_EQ(bad_gl.exit_code, 2);
  EXPECT_NE(bad_gl.output.find("--gl"), std::string::npos) << bad_gl.output;
  const test::CommandResult ui_without_gl =
      test::run_lueur("--headless --size 16x16 --frames 1 --ui --out " + dir + "/ui.png");
  EXPECT_EQ(ui_without_gl.exit_code, 2);
  EXPECT_FALSE(test::file_exists(dir + "/ui.png"));
}

}  // namespace
}  // namespace lueur
