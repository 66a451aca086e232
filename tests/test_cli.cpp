// The lueur executable end to end: bad input of every kind gives one line naming the problem and exit status 2,
// with no output file left behind; good input writes PNG, PFM and EXR and prints the path.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "image/image_output.h"
#include "test_support.h"

namespace lueur {
namespace {

class Cli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::make_temp_dir("cli"); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  /// Runs a headless render expected to fail; checks status 2, a single error line mentioning `needle`, and that
  /// no output was written. The arguments come last: an option given twice takes its last value.
  void expect_refused(const std::string& arguments, const std::string& needle) {
    const std::string out = dir_ + "/out.png";
    const test::CommandResult r = test::run_lueur("--headless --out '" + out + "' --size 8x8 --frames 1 " + arguments);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("lueur: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.output;
    // One line of error (warnings may precede it).
    const size_t error_at = r.output.find("lueur: error: ");
    if (error_at != std::string::npos) {
      EXPECT_EQ(r.output.find('\n', error_at), r.output.size() - 1) << r.output;
    }
    EXPECT_FALSE(test::file_exists(out));
  }
  std::string dir_;
};

using test::shell_quote;

const char* kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

TEST_F(Cli, RefusesMissingFilesAndDirectories) {
  expect_refused(shell_quote(dir_ + "/nope.obj"), "nope.obj");
  expect_refused(shell_quote(dir_), dir_);
}

TEST_F(Cli, RefusesMalformedScenesNamingFileAndLine) {
  expect_refused(shell_quote(write("garbage.obj", std::string(kQuad) + "this is not obj\n")), "garbage.obj:6");
  expect_refused(shell_quote(write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")), "range.obj:4");
  expect_refused(shell_quote(write("negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n")), "negative.obj:4");
  expect_refused(shell_quote(write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")), "nan.obj:2");
  expect_refused(shell_quote(write("inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n")), "inf.obj:2");
  expect_refused(shell_quote(write("empty.obj", "")), "empty.obj");
  expect_refused(shell_quote(write("points.obj", "v 0 0 0\nv 1 0 0\n")), "points.obj");
  expect_refused(shell_quote(write("binary.obj", std::string("v 0 0 0\n\x01\x02\x00\xff\xfe", 13))), "binary.obj");
}

TEST_F(Cli, RefusesBadOptions) {
  expect_refused("--lights sideways", "--lights");
  expect_refused("--size 0x5", "--size");
  expect_refused("--size big", "--size");
  expect_refused("--frames 0", "--frames");
  expect_refused("--l1-rays -3", "--l1-rays");
  expect_refused("--blinn-k 1.5", "--blinn-k");
  expect_refused("--smooth-normals maybe", "--smooth-normals");
  expect_refused("--passes le,l9", "--passes");
  expect_refused("--weights l1=heavy", "--weights");
  expect_refused("--camera '1 2 3'", "--camera");
  expect_refused("--up '0 0 0'", "--up");
  expect_refused("--bogus", "bogus");
  // NaN passes any range check written as comparisons, so each real-valued option must refuse it by name.
  for (const char* option : {"--ao-radius", "--blinn-k", "--recompute-ratio", "--exposure"}) {
    expect_refused(std::string(option) + " nan", std::string(option) + ": 'nan' is not a finite number");
    expect_refused(std::string(option) + " inf", std::string(option) + ": 'inf' is not a finite number");
    expect_refused(std::string(option) + " 0.5x", std::string(option) + ": '0.5x' is not a finite number");
  }
  expect_refused("--ao-radius -2", "--ao-radius: '-2' is outside [0, 1e+30]");  // 0: automatic, as in the panel
  expect_refused("--recompute-ratio 17", "--recompute-ratio: '17' is outside [0, 16]");
  expect_refused("--cache-mb 0", "--cache-mb: '0' is outside [1, 1048576]");  // whole bounds in full, not 1.04858e+06
  expect_refused("--seed -1", "--seed: '-1' is not a non-negative integer");
  expect_refused("--frame-limit -1", "--frame-limit: '-1' is not a non-negative integer");
  // The program's own options in the same words (CLI11's range check let 'nan' through for --checkpoint).
  expect_refused("--checkpoint nan", "--checkpoint: 'nan' is not a finite number");
  expect_refused("--checkpoint -1", "--checkpoint: '-1' is outside [0, 1000000000]");
  expect_refused("--threads 1.5", "--threads: '1.5' is not a non-negative integer");
  expect_refused("--threads 2000", "--threads: '2000' is outside [0, 1024]");
  const test::CommandResult r = test::run_lueur("--headless");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--out"), std::string::npos);
}

TEST_F(Cli, RefusesUnwritableOutputsBeforeRendering) {
  for (const std::string& out : {dir_ + "/no/such/dir/x.png", dir_ + "/x.bmp", dir_}) {
    const test::CommandResult r = test::run_lueur("--headless --size 8x8 --frames 1 --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("cannot write"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("frame 1/1"), std::string::npos) << "should refuse before rendering: " << r.output;
  }
}

TEST_F(Cli, WritesPngPfmAndExrAndPrintsThePath) {
  const std::string scene = write("tri.obj", std::string("mtllib tri.mtl\n") + kQuad);
  write("tri.mtl", "newmtl m\nKd 0.5 0.5 0.5\n");
  for (const char* ext : {".png", ".pfm", ".exr"}) {
    const std::string out = dir_ + "/image" + ext;
    const test::CommandResult r =
        test::run_lueur("'" + scene + "' --headless --size 16x12 --frames 2 --threads 2 --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(out), std::string::npos);
    EXPECT_NE(r.output.find("Mrays/s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("default light rig"), std::string::npos) << r.output;  // the file has no emitter
    ASSERT_TRUE(test::file_exists(out));
  }
  const Image pfm = decode_pfm(test::read_file(dir_ + "/image.pfm"));
  EXPECT_EQ(pfm.width, 16);
  EXPECT_EQ(pfm.height, 12);
  float brightest = 0.0f;
  for (const float v : pfm.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    brightest = std::max(brightest, v);
  }
  EXPECT_GT(brightest, 0.0f);  // the default light reaches the quad
}

TEST_F(Cli, DefaultSceneRendersWithEveryStrategy) {
  for (const char* lights : {"all", "uniform", "area", "power", "importance"}) {
    const std::string out = dir_ + "/default-" + lights + ".png";
    const test::CommandResult r = test::run_lueur(
        std::string("--headless --size 24x24 --frames 1 --l1-rays 2 --lights ") + lights + " --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_TRUE(test::file_exists(out));
  }
}

// An empty --passes renders (the panel allows unchecking every pass) but says why the image is black; a pass named
// says nothing of the kind.
TEST_F(Cli, EmptyPassesWarnThatTheImageIsBlack) {
  const std::string out = dir_ + "/black.pfm";
  const test::CommandResult none = test::run_lueur("--headless --size 8x8 --frames 1 --passes '' --out '" + out + "'");
  ASSERT_EQ(none.exit_code, 0) << none.output;
  EXPECT_NE(none.output.find("warning: --passes names no pass"), std::string::npos) << none.output;
  const Image image = decode_pfm(test::read_file(out));
  for (const float v : image.rgb) ASSERT_EQ(v, 0.0f);
  const test::CommandResult some = test::run_lueur("--headless --size 8x8 --frames 1 --passes ao --out '" + out + "'");
  ASSERT_EQ(some.exit_code, 0) << some.output;
  EXPECT_EQ(some.output.find("names no pass"), std::string::npos) << some.output;
}

// An option given twice takes its last value: the image is byte for byte the one the last values alone give, and
// only the last --out is written.
TEST_F(Cli, RepeatedOptionsTakeTheirLastValue) {
  const std::string first = dir_ + "/first.pfm", last = dir_ + "/last.pfm", alone = dir_ + "/alone.pfm";
  const test::CommandResult repeated = test::run_lueur(
      "--headless --headless --size 8x8 --size 12x10 --frames 3 --frames 1 --lights uniform --lights area "
      "--passes ao --passes l1,l2 --seed 5 --seed 9 --out '" +
      first + "' --out '" + last + "'");
  ASSERT_EQ(repeated.exit_code, 0) << repeated.output;
  EXPECT_FALSE(test::file_exists(first));
  const test::CommandResult single =
      test::run_lueur("--headless --size 12x10 --frames 1 --lights area --passes l1,l2 --seed 9 --out '" + alone + "'");
  ASSERT_EQ(single.exit_code, 0) << single.output;
  const Image image = decode_pfm(test::read_file(last));
  EXPECT_EQ(image.width, 12);
  EXPECT_EQ(image.height, 10);
  EXPECT_EQ(test::read_file(last), test::read_file(alone));
}

// scripts/run.sh passes its own --out (and --gl auto) before the user's options: the user's win. With no display
// it renders headless and prints the path of the file it wrote.
TEST_F(Cli, RunScriptTakesTheUsersOptions) {
  const std::string out = dir_ + "/mine.png";
  const std::string build = std::string(LUEUR_EXECUTABLE).substr(0, std::string(LUEUR_EXECUTABLE).rfind('/'));
  const test::CommandResult r =
      test::run_program(std::string(LUEUR_SOURCE_DIR) + "/scripts/run.sh",
                        "--out " + shell_quote(out) + " --gl none --size 8x6 --frames 1 --l1-rays 1 --l2-rays 1",
                        "env -u DISPLAY -u WAYLAND_DISPLAY LUEUR_BUILD=" + shell_quote(build));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(test::file_exists(out)) << r.output;
  EXPECT_NE(r.output.find(out), std::string::npos) << r.output;
  const std::string png = test::read_file(out);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  // The width and height of the IHDR chunk, big-endian.
  const auto be32 = [&](size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(png[at + i]);
    return v;
  };
  EXPECT_EQ(be32(16), 8u);
  EXPECT_EQ(be32(20), 6u);
}

// A time limit stops after the frame in flight; the image then holds the frames done, and renders again exactly
// from them.
TEST_F(Cli, TimeLimitStopsEarlyAndTheImageSaysHowManyFrames) {
  const std::string limited = dir_ + "/limited.pfm", again = dir_ + "/again.pfm";
  const test::CommandResult r =
      test::run_lueur("--headless --size 16x16 --frames 1000000 --time-limit 0.2 --out '" + limited + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const size_t at = r.output.find("time limit of 0.2 s reached after ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const int frames = std::stoi(r.output.substr(at + std::string("time limit of 0.2 s reached after ").size()));
  EXPECT_GE(frames, 1);
  EXPECT_LT(frames, 1000000);
  const test::CommandResult full =
      test::run_lueur("--headless --size 16x16 --frames " + std::to_string(frames) + " --out '" + again + "'");
  ASSERT_EQ(full.exit_code, 0) << full.output;
  EXPECT_EQ(test::read_file(limited), test::read_file(again));
}

TEST_F(Cli, ExportedDefaultSceneMatchesTheCommittedAsset) {
  const std::string out = dir_ + "/cornell-apple.obj";
  const test::CommandResult r = test::run_lueur("--export-default-scene '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(test::read_file(out), test::read_file(std::string(LUEUR_SOURCE_DIR) + "/assets/cornell-apple.obj"));
  EXPECT_EQ(test::read_file(dir_ + "/cornell-apple.mtl"),
            test::read_file(std::string(LUEUR_SOURCE_DIR) + "/assets/cornell-apple.mtl"));
}

TEST_F(Cli, AnExportedSceneRendersTheSameBytesAsTheSceneFromTheViewItPrints) {
  // No emitter (so the light rig is added) and no normals (so smooth ones are computed): a shallow hexagonal
  // pyramid, whose faces meet at less than the crease angle, above a floor.
  const std::string scene = write("model.obj",
                                  "v 0 1.3 0\nv 1 1 0\nv 0.5 1 0.866\nv -0.5 1 0.866\nv -1 1 0\nv -0.5 1 -0.866\n"
                                  "v 0.5 1 -0.866\nf 1 3 2\nf 1 4 3\nf 1 5 4\nf 1 6 5\nf 1 7 6\nf 1 2 7\n"
                                  "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nf 8 10 9\nf 8 11 10\n");
  const std::string exported = dir_ + "/exported scene.obj";
  const test::CommandResult r = test::run_lueur("'" + scene + "' --size 48x32 --export-scene '" + exported + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(exported + "\n"), std::string::npos) << r.output;
  const size_t at = r.output.find("--camera \"");
  ASSERT_NE(at, std::string::npos) << r.output;
  const size_t end = r.output.find('\n', at);
  const std::string view_options = r.output.substr(at, end - at);  // --camera "..." --ao-radius R
  const std::string obj = test::read_file(exported), mtl = test::read_file(dir_ + "/exported scene.mtl");
  EXPECT_NE(obj.find("\nvn "), std::string::npos) << "the computed normals are written";
  EXPECT_NE(mtl.find("lueur-sky-top"), std::string::npos) << "the light rig is written";

  const std::string render = " --headless --size 48x32 --frames 3 --passes le,l1,l2,ao " + view_options;
  const test::CommandResult original = test::run_lueur("'" + scene + "'" + render + " --out '" + dir_ + "/a.pfm'");
  const test::CommandResult again = test::run_lueur("'" + exported + "'" + render + " --out '" + dir_ + "/b.pfm'");
  ASSERT_EQ(original.exit_code, 0) << original.output;
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("warning"), std::string::npos) << "the export needs no rig: " << again.output;
  EXPECT_TRUE(test::read_file(dir_ + "/a.pfm") == test::read_file(dir_ + "/b.pfm")) << "the images differ";
}

TEST_F(Cli, AnExportThatCannotBeWrittenIsOneLineAndLeavesNothing) {
  ASSERT_EQ(::mkdir((dir_ + "/folder.obj").c_str(), 0755), 0);
  for (const auto& [path, why] : {std::pair<std::string, std::string>{dir_ + "/absent/scene.obj", "no directory"},
                                  {dir_ + "/folder.obj", "it is a directory"},
                                  {dir_ + "/scene.mtl", "an export is an OBJ file"},
                                  {dir_ + "/scene", "an export is an OBJ file"}}) {
    for (const char* option : {"--export-scene", "--export-default-scene"}) {
      const test::CommandResult r = test::run_lueur(std::string(option) + " '" + path + "'");
      EXPECT_EQ(r.exit_code, 2) << r.output;
      EXPECT_EQ(r.output, "lueur: error: cannot write '" + path + "': " + why +
                              (why == "no directory" ? " '" + dir_ + "/absent'" : why == "an export is an OBJ file"
                                                                                       ? " (name it FILE.obj)"
                                                                                       : "") +
                              "\n");
    }
  }
  // Nothing was written: no MTL beside a refused OBJ (the folder made above is all there is).
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir_)) left.push_back(entry.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"folder.obj"});
}

}  // namespace
}  // namespace lueur
