// View files: a saved view renders the same image again headless, and bad view files are refused with a message
// naming the field.
#include <gtest/gtest.h>

#include <fstream>
#include <utility>

#include "settings/view_file.h"
#include "test_support.h"

namespace lueur {
namespace {

CameraSpec test_camera() { return CameraSpec{Vec3(1.0f, 2.0f, 5.0f), Vec3(0.0f, 0.5f, 0.0f), Vec3(0, 1, 0), 40.0f}; }

TEST(ViewFile, RoundTripsThroughJson) {
  Settings v;
  v.camera = test_camera();
  v.render.width = 123;
  v.render.height = 45;
  v.render.enabled = {false, true, false, true};
  v.render.lights = LightStrategy::kPower;
  v.render.reuse = ReuseMode::kAverage;
  v.render.seed = 18446744073709551557ull;  // beyond 2^53: must survive JSON exactly
  v.weights = {0.5f, 0.25f, 2.0f, 1.5f};
  v.layer = Layer::kL2Reused;
  v.accel = AccelKind::kEmbree;
  v.up = Vec3(0.0f, 0.0f, 1.0f);
  v.display = {1.25f, ToneMap::kAces};
  v.smooth_normals = false;
  v.frame_limit = 100;
  v.frames = 37;
  EXPECT_EQ(view_from_json(view_to_json(v)), v);
}

TEST(ViewFile, RefusesBadFilesNamingTheField) {
  const auto message = [](const std::string& text) {
    try {
      view_from_json(text);
    } catch (const ViewFileError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(message("{\"width\": 5}").find("not a Lueur view"), std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"width\": -5}").find("'width'"), std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"lights\": \"sun\"}").find("'lights'"), std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"passes\": [\"l3\"]}").find("'passes'"), std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"camera\": {\"eye\": [1, 2]}}").find("camera.eye"), std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"camera\": {\"eye\": [0,0,0], \"target\": [0,0,0]}}").find("same point"),
            std::string::npos);
  EXPECT_NE(message("{\"lueur_view\":1, \"exposure\": 99}").find("exposure"), std::string::npos);
}

TEST(ViewFile, AViewFileRendersTheSameImageAsTheOptionsItHolds) {
  const std::string dir = test::make_temp_dir("view-file");
  Settings v;
  v.camera = CameraSpec{Vec3(278, 273, -600), Vec3(300, 200, 0), Vec3(0, 1, 0), 45.0f};
  v.render.width = 40;
  v.render.height = 30;
  v.render.l1_rays = 3;
  v.render.l2_rays = 2;
  v.render.lights = LightStrategy::kUniform;
  v.render.seed = 11;
  v.weights = {1.0f, 0.8f, 0.3f, 1.0f};
  v.display.exposure = 0.5f;
  v.frames = 3;
  save_view_file(dir + "/view.json", v);
  const test::CommandResult from_file =
      test::run_lueur("--headless --view-file " + dir + "/view.json --out " + dir + "/from-file.pfm");
  ASSERT_EQ(from_file.exit_code, 0) << from_file.output;
  const test::CommandResult from_options = test::run_lueur(
      "--headless --size 40x30 --frames 3 --l1-rays 3 --l2-rays 2 --lights uniform --seed 11 "
      "--weights le=1,l1=0.8,l2=0.3 --camera \"278 273 -600 300 200 0 45\" --out " +
      dir + "/from-options.pfm");
  ASSERT_EQ(from_options.exit_code, 0) << from_options.output;
  EXPECT_EQ(test::read_file(dir + "/from-file.pfm"), test::read_file(dir + "/from-options.pfm"));

  // An option given next to the file wins over the file.
  const test::CommandResult overridden =
      test::run_lueur("--headless --view-file " + dir + "/view.json --seed 12 --out " + dir + "/seed12.pfm");
  ASSERT_EQ(overridden.exit_code, 0) << overridden.output;
  EXPECT_NE(test::read_file(dir + "/seed12.pfm"), test::read_file(dir + "/from-file.pfm"));

  std::ofstream(dir + "/bad.json") << "{\"lueur_view\": 1, \"reuse\": \"sometimes\"}";
  const test::CommandResult bad =
      test::run_lueur("--headless --view-file " + dir + "/bad.json --out " + dir + "/x.png");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("'reuse'"), std::string::npos) << bad.output;
  EXPECT_FALSE(test::file_exists(dir + "/x.png"));
  const test::CommandResult missing =
      test::run_lueur("--headless --view-file " + dir + "/nope.json --out " + dir + "/x.png");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("nope.json"), std::string::npos) << missing.output;
  // Not a regular file: one line at once, where /dev/zero used to be read until the process was killed.
  for (const auto& [path, reason] : {std::pair<std::string, std::string>{"/dev/zero", "not a regular file"},
                                     std::pair<std::string, std::string>{dir, "Is a directory"}}) {
    const test::CommandResult r = test::run_lueur("--headless --view-file " + path + " --out " + dir + "/x.png");
    EXPECT_EQ(r.exit_code, 2) << path;
    EXPECT_NE(r.output.find("--view-file: cannot open '" + path + "': " + reason), std::string::npos) << r.output;
  }
  // A file far larger than any view is refused before it is read.
  {
    std::ofstream big(dir + "/big.json");
    big << std::string((16u << 20) + 1, ' ');
  }
  const test::CommandResult big =
      test::run_lueur("--headless --view-file " + dir + "/big.json --out " + dir + "/x.png");
  EXPECT_EQ(big.exit_code, 2);
  EXPECT_NE(big.output.find("big.json' is 16.0 MiB, more than"), std::string::npos) << big.output;
  EXPECT_FALSE(test::file_exists(dir + "/x.png"));
}

}  // namespace
}  // namespace lueur
