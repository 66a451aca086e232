// Mirrors, glass and the further-bounce pass changed nothing else: a scene without a mirror or glass, rendered with
// ln off, gives the bytes the version before them gave (commit 8be0810, the same compiler and settings), on the
// default scene and CornellBox-Original, with the defaults and with the store, the head-light's absence, AO and one
// Le ray. The figures are FNV-1a hashes of the PFM files that version wrote; the store's case was written again
// when its cells began to keep learning (issue 51: a share of the hits on a ready cell feed it), which changes its
// images on purpose.
#include <gtest/gtest.h>

#include "core/byte_stream.h"
#include "test_support.h"

namespace lueur {
namespace {

struct Case {
  const char* options;
  uint64_t default_scene, cornell_original;
};

constexpr Case kCases[] = {
    {"--size 64x48 --frames 5", 0xe29da6c4345bbc21ull, 0x8489646deadb458dull},
    {"--size 64x48 --frames 3 --le-rays 1 --passes le,l1,l2,ao --reuse screen+cache", 0xbbe38f0340321f8aull,
     0xfbae31b6502e3014ull},
};

uint64_t render_hash(const std::string& scene, const std::string& options, const std::string& out) {
  const auto run = test::run_lueur("--headless " + scene + " " + options + " --out " + test::shell_quote(out));
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return fnv1a64(test::read_file(out));
}

TEST(UnchangedImages, TheDefaultSceneIsTheBytesItWasBeforeMirrorsAndGlass) {
  const std::string dir = test::make_temp_dir("unchanged-default");
  for (const Case& c : kCases)
    EXPECT_EQ(render_hash("", c.options, dir + "/default.pfm"), c.default_scene) << c.options;
}

TEST(UnchangedImages, CornellBoxOriginalIsTheBytesItWasBeforeMirrorsAndGlass) {
  const std::string obj = test::shared_scene("cornell-original/CornellBox-Original.obj");
  if (obj.empty()) GTEST_SKIP() << "../shared/scenes not present";
  const std::string dir = test::make_temp_dir("unchanged-cornell");
  for (const Case& c : kCases)
    EXPECT_EQ(render_hash(test::shell_quote(obj), c.options, dir + "/cornell.pfm"), c.cornell_original) << c.options;
}

}  // namespace
}  // namespace lueur
