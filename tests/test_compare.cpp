// The A/B split (--compare SETTING=VALUE): each side's pixels are exactly those of a full render with that side's
// settings, bad comparisons are refused in one line, and the two sides of the window take turns frame by frame.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "image/image_output.h"
#include "runtime/frame_turns.h"
#include "settings/compare.h"
#include "settings/setting_table.h"
#include "test_support.h"

namespace lueur {
namespace {

constexpr const char* kSmall = "--size 40x24 --frames 6 --l1-rays 4 --l2-rays 4 --passes le,l1,l2,ao";

Image render_pfm(const std::string& dir, const std::string& name, const std::string& arguments) {
  const std::string path = dir + "/" + name + ".pfm";
  const test::CommandResult run = test::run_lueur("--headless --out " + path + " " + kSmall + " " + arguments);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return decode_pfm(test::read_file(path));
}

/// Whether columns [x0, x1) of a and b hold the same bytes.
bool same_columns(const Image& a, const Image& b, int x0, int x1) {
  for (int y = 0; y < a.height; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(a.width) + static_cast<size_t>(x)) + c;
        if (std::memcmp(&a.rgb[i], &b.rgb[i], sizeof(float)) != 0) return false;
      }
  return true;
}

struct Case {
  std::string compare, left_option, right_option;
};

TEST(Compare, EachSideIsBitIdenticalToAFullRenderWithItsSettings) {
  const std::string dir = test::make_temp_dir("compare_sides");
  // Settings that read no other pixel, and screen-space reuse, which does: each side renders the whole image, so
  // the right side's L2 borrows L1 from its own pixels on both sides of the divider, as a full render does.
  const std::vector<Case> cases = {{"lights=uniform", "--lights area", "--lights uniform"},
                                   {"sampler=independent", "", "--sampler independent"},
                                   {"l1-rays=8", "", "--l1-rays 8"},
                                   {"reuse=off", "", "--reuse off"},
                                   {"seed=5", "", "--seed 5"}};
  for (const Case& c : cases) {
    const Image split = render_pfm(dir, "split", "--compare " + c.compare + " --compare-split 0.3 " + c.left_option);
    const Image left = render_pfm(dir, "left", c.left_option);
    const Image right = render_pfm(dir, "right", c.right_option);
    ASSERT_EQ(split.width, 40);
    const int column = split_column(0.3f, 40);
    EXPECT_EQ(column, 12);
    EXPECT_TRUE(same_columns(split, left, 0, column)) << c.compare;
    EXPECT_TRUE(same_columns(split, right, column, split.width)) << c.compare;
    EXPECT_FALSE(same_columns(split, left, column, split.width)) << c.compare << ": the right side did not change";
  }
}

TEST(Compare, TheSplitHoldsForEveryLayerOfAnExrAndThePngShowsTheDivider) {
  const std::string dir = test::make_temp_dir("compare_png");
  const test::CommandResult png = test::run_lueur("--headless --out " + dir + "/split.png " + std::string(kSmall) +
                                                  " --compare lights=uniform --compare-split 0.5");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  EXPECT_NE(png.output.find("left (as set): "), std::string::npos) << png.output;
  EXPECT_NE(png.output.find("right (lights=uniform): "), std::string::npos) << png.output;
  EXPECT_NE(png.output.find("relMSE x seconds"), std::string::npos) << png.output;
  const std::string bytes = test::read_file(dir + "/split.png");
  int width = 0, height = 0, channels = 0;
  uint8_t* pixels = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                          static_cast<int>(bytes.size()), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr);
  const std::vector<uint8_t> rgb(pixels, pixels + 3 * static_cast<size_t>(width) * static_cast<size_t>(height));
  stbi_image_free(pixels);
  ASSERT_EQ(width, 40);
  // Columns 19 and 20 (the divider, two pixels wide at the split) are light grey on every row.
  for (int y = 0; y < 24; ++y)
    for (int x = 19; x <= 20; ++x) EXPECT_EQ(rgb[3 * (static_cast<size_t>(y) * 40 + static_cast<size_t>(x))], 230);
}

TEST(Compare, RefusesWhatCannotBeComparedInOneLine) {
  for (const std::string bad : {"nonsense=1", "size=8x8", "camera=inside", "lights=sideways", "lights"}) {
    const test::CommandResult run = test::run_lueur("--headless --out /tmp/never.png --compare " + bad);
    EXPECT_EQ(run.exit_code, 2) << bad << ": " << run.output;
    EXPECT_NE(run.output.find("--compare: "), std::string::npos) << run.output;
  }
  EXPECT_TRUE(comparable("lights"));
  EXPECT_TRUE(comparable("reuse"));
  EXPECT_TRUE(comparable("sampler"));
  EXPECT_FALSE(comparable("exposure"));  // a display setting: both sides would show the same estimate
  EXPECT_FALSE(comparable("size"));
}

TEST(Compare, ComparedSettingsChangeOnlyTheOneSetting) {
  Settings settings;
  settings.compare = "l2-rays=3";
  settings.render.l1_rays = 7;
  const std::optional<Settings> right = compared_settings(settings);
  ASSERT_TRUE(right);
  EXPECT_EQ(right->render.l2_rays, 3);
  EXPECT_EQ(right->render.l1_rays, 7);
  EXPECT_TRUE(right->compare.empty());
  settings.compare.clear();
  EXPECT_FALSE(compared_settings(settings));
}

TEST(FrameTurns, TwoTracersThatAskAgainAtOnceShareTheTurns) {
  // Each side asks again as soon as its turn ends. A plain mutex would hand the turn back to the side that just
  // released it most of the time; turns taken in order alternate while both are asking.
  FrameTurns turns;
  std::vector<int> order;
  std::atomic<int> ready{0};
  const auto side = [&](int id) {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();  // start together
    for (int k = 0; k < 300; ++k) {
      const FrameTurn turn(&turns);
      order.push_back(id);                                         // only ever touched inside a turn
      std::this_thread::sleep_for(std::chrono::microseconds(50));  // a frame's work, so that the other side asks
    }
  };
  std::thread a(side, 0), b(side, 1);
  a.join();
  b.join();
  ASSERT_EQ(order.size(), 600u);
  // While both were asking (from the later side's first turn to the first side's last), the turns nearly alternate.
  size_t begin = 0;
  while (order[begin] == order[0]) ++begin;
  size_t end = order.size() - 1;
  while (order[end] == order.back()) --end;
  int repeats = 0;
  for (size_t k = begin + 1; k <= end; ++k) repeats += order[k] == order[k - 1];
  EXPECT_LT(repeats, static_cast<int>(end - begin) / 10) << "of " << end - begin << " turns";
  EXPECT_GT(end - begin, 100u);  // both really were asking at once
}

}  // namespace
}  // namespace lueur
