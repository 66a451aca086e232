// The window's pixel inspector reads what the film holds at the pixel under the mouse: the right pixel of a view that
// stretches the film over the window, each rendered layer's average there, and exactly the image's linear value.
#include <gtest/gtest.h>

#include <cmath>

#include "film/pixel_probe.h"

namespace lueur {
namespace {

TEST(FilmPixelAt, MapsAViewThatStretchesTheFilmOverIt) {
  // A film of 4 x 2 shown over a view of 400 x 100: each film pixel covers 100 x 50 view pixels.
  EXPECT_EQ(film_pixel_at(0.0, 0.0, 400, 100, 4, 2), (FilmPixel{0, 0}));
  EXPECT_EQ(film_pixel_at(99.9, 49.9, 400, 100, 4, 2), (FilmPixel{0, 0}));
  EXPECT_EQ(film_pixel_at(100.0, 50.0, 400, 100, 4, 2), (FilmPixel{1, 1}));
  EXPECT_EQ(film_pixel_at(399.99, 99.99, 400, 100, 4, 2), (FilmPixel{3, 1}));
  EXPECT_EQ(film_pixel_at(250.0, 10.0, 400, 100, 4, 2), (FilmPixel{2, 0}));
  // A preview at an eighth of the size: the same point, the coarser pixel.
  EXPECT_EQ(film_pixel_at(256.0, 300.0, 512, 512, 64, 64), (FilmPixel{32, 37}));
  for (const auto& [x, y] : {std::pair{-0.5, 10.0}, {400.0, 10.0}, {10.0, -1.0}, {10.0, 100.0}, {NAN, 1.0}})
    EXPECT_FALSE(film_pixel_at(x, y, 400, 100, 4, 2).has_value()) << x << ", " << y;
  EXPECT_FALSE(film_pixel_at(1.0, 1.0, 0, 100, 4, 2).has_value());
  EXPECT_FALSE(film_pixel_at(1.0, 1.0, 400, 100, 0, 0).has_value());
}

class Probe : public ::testing::Test {
 protected:
  void SetUp() override {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.enabled = {true, true, true, false};  // Le, L1, L2; L2 with frame reuse adds its explaining layers
    film_.reset(settings);
    film_.unit = 0x1p-32;
  }

  /// One frame where each rendered layer holds a value of its own at each pixel.
  void add_frame(float frame) {
    std::array<std::vector<Vec3>, kLayerCount> values;
    for (size_t l = 0; l < static_cast<size_t>(kLayerCount); ++l) {
      if (film_.sums[l].empty()) continue;
      for (int i = 0; i < kWidth * kHeight; ++i)
        values[l].push_back(Vec3(0.01f * static_cast<float>(l) + 0.1f * static_cast<float>(i), frame, 0.5f));
    }
    ASSERT_EQ(film_.add_frame(values), 0u);
  }

  static constexpr int kWidth = 5, kHeight = 3;
  Film film_;
  std::array<bool, kPassCount> enabled_ = {true, true, true, false};
  std::array<float, kPassCount> weights_ = {1.0f, 0.6f, 0.4f, 1.0f};
};

TEST_F(Probe, NothingBeforeTheFirstFrameOrOutsideTheFilm) {
  EXPECT_FALSE(probe_pixel(film_, {0, 0}, enabled_, weights_).has_value());
  add_frame(1.0f);
  EXPECT_TRUE(probe_pixel(film_, {4, 2}, enabled_, weights_).has_value());
  for (const FilmPixel outside : {FilmPixel{5, 0}, FilmPixel{0, 3}, FilmPixel{-1, 0}, FilmPixel{0, -1}})
    EXPECT_FALSE(probe_pixel(film_, outside, enabled_, weights_).has_value()) << outside.x << ", " << outside.y;
}

TEST_F(Probe, ReadsEachLayersAverageAndExactlyTheImagesValueAtThePixel) {
  add_frame(1.0f);
  add_frame(2.0f);
  add_frame(6.0f);
  const FilmPixel pixel{3, 1};  // index 8, row-major from the top
  const std::optional<PixelProbe> probe = probe_pixel(film_, pixel, enabled_, weights_);
  ASSERT_TRUE(probe.has_value());
  EXPECT_EQ(probe->pixel, pixel);
  EXPECT_EQ(probe->frames, 3u);
  for (size_t l = 0; l < static_cast<size_t>(kLayerCount); ++l) {
    SCOPED_TRACE(kLayerNames[l]);
    ASSERT_EQ(probe->layers[l].has_value(), !film_.sums[l].empty());
    if (!probe->layers[l]) continue;
    // The three frames' values: the layer's own red, the frames' mean (3) in green, 0.5 in blue.
    EXPECT_NEAR(probe->layers[l]->r, 0.01f * static_cast<float>(l) + 0.8f, 1e-6f);
    EXPECT_NEAR(probe->layers[l]->g, 3.0f, 1e-6f);
    EXPECT_NEAR(probe->layers[l]->b, 0.5f, 1e-6f);
    EXPECT_EQ(*probe->layers[l], layer_average(film_, static_cast<Layer>(l)).at(pixel.x, pixel.y));
  }
  EXPECT_FALSE(probe->layers[static_cast<size_t>(Layer::kAo)].has_value()) << "AO is not rendered";
  // Bit for bit the value of the image the display and the saved files are made from.
  EXPECT_EQ(probe->combined, combine_passes(film_, enabled_, weights_).at(pixel.x, pixel.y));
  EXPECT_NEAR(probe->combined.g, (1.0f + 0.6f + 0.4f) * 3.0f, 1e-5f);

  // A pass switched off leaves the combination, not the layers.
  enabled_[static_cast<size_t>(Pass::kL2)] = false;
  const PixelProbe without_l2 = *probe_pixel(film_, pixel, enabled_, weights_);
  EXPECT_NEAR(without_l2.combined.g, (1.0f + 0.6f) * 3.0f, 1e-5f);
  EXPECT_TRUE(without_l2.layers[static_cast<size_t>(Layer::kL2)].has_value());
}

}  // namespace
}  // namespace lueur
