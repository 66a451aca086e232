// --checkpoint and --resume: a render stopped or killed at any frame and resumed ends with the bytes of an
// uninterrupted one, in every output format, with the L1 store and an A/B split; a state that does not match the
// options is refused with one line naming what differs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "test_support.h"

namespace lueur {
namespace {

using test::file_exists;
using test::make_temp_dir;
using test::read_file;
using test::run_lueur;
using test::shell_quote;

struct ResumeCase {
  const char* name;
  const char* options;
  const char* extension;
};

class Resume : public ::testing::TestWithParam<ResumeCase> {};

TEST_P(Resume, AKilledRenderResumedGivesTheUninterruptedBytes) {
  const ResumeCase& c = GetParam();
  const std::string dir = make_temp_dir(std::string("resume_") + c.name);
  const std::string base = std::string("--headless --size 64x48 ") + c.options;
  const std::string whole = dir + "/whole." + c.extension, part = dir + "/part." + c.extension;

  // Killed (SIGKILL: no chance to tidy up) once its first checkpoint is there. It was asked for far more frames than
  // any machine renders by then, so it is still running when the kill comes, however fast or loaded the machine.
  const std::string state = part + ".lueur-state";
  const std::string script = shell_quote(LUEUR_EXECUTABLE) + " " + base +
                             " --frames 1000000 --threads 1 --checkpoint 0.02 --out " + shell_quote(part) +
                             " & pid=$!; while [ ! -f " + shell_quote(state) + " ]; do sleep 0.01; done; kill -9 $pid;" +
                             " wait $pid";
  const auto killed = test::run_program("sh", "-c " + shell_quote(script));
  EXPECT_NE(killed.exit_code, 0) << "the render finished before it could be killed: " << killed.output;
  ASSERT_TRUE(file_exists(state));
  ASSERT_TRUE(file_exists(part));  // the image so far, whole (written atomically)

  // Resumed on another thread count to 40 frames, or, where the killed run got further, 8 frames past where it was.
  int frames = 40;
  const std::string resume = " --threads 2 --out " + shell_quote(part) + " --resume " + shell_quote(state);
  auto resumed = run_lueur(base + " --frames 40" + resume);
  const std::string further = "it already holds ";
  if (const size_t at = resumed.output.find(further); resumed.exit_code != 0 && at != std::string::npos) {
    frames = std::stoi(resumed.output.substr(at + further.size())) + 8;
    resumed = run_lueur(base + " --frames " + std::to_string(frames) + resume);
  }
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  const auto uninterrupted =
      run_lueur(base + " --frames " + std::to_string(frames) + " --threads 2 --out " + shell_quote(whole));
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.output;
  EXPECT_EQ(read_file(part), read_file(whole)) << "the resumed image differs from the uninterrupted one";
}

// PFM and EXR hold the float sums (the EXR every pass, ln too); PNG goes through the tone map; the store carries
// state from frame to frame; an A/B split resumes both sides.
INSTANTIATE_TEST_SUITE_P(Outputs, Resume,
                         ::testing::Values(ResumeCase{"pfm", "", "pfm"},
                                           ResumeCase{"exr", "--passes le,l1,l2,ao,ln --ln-rays 2", "exr"},
                                           ResumeCase{"png_sobol", "--sampler sobol", "png"},
                                           ResumeCase{"store", "--reuse screen+cache", "pfm"},
                                           ResumeCase{"split", "--compare lights=uniform", "png"}),
                         [](const ::testing::TestParamInfo<ResumeCase>& p) { return std::string(p.param.name); });

TEST(ResumeRefused, AStateThatDoesNotMatchTheOptionsIsRefusedWithOneLine) {
  const std::string dir = make_temp_dir("resume_refused");
  const std::string out = dir + "/out.pfm", state = out + ".lueur-state";
  const std::string base = "--headless --size 32x24 --out " + shell_quote(out);
  ASSERT_EQ(run_lueur(base + " --frames 6 --checkpoint 100").exit_code, 0);
  ASSERT_TRUE(file_exists(state));

  const auto refused = [&](const std::string& options, const std::string& message) {
    const auto r = run_lueur(base + " " + options);
    EXPECT_EQ(r.exit_code, 2) << options;
    EXPECT_NE(r.output.find(message), std::string::npos) << options << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  };
  const std::string resume = " --resume " + shell_quote(state);
  refused("--frames 6 --l1-rays 4" + resume, "it was rendered with --l1-rays 16, not --l1-rays 4");
  refused("--frames 6 --seed 9" + resume, "--seed");
  refused("--frames 4" + resume, "it already holds 6 frames, more than --frames 4");
  refused("--frames 6 --size 32x20" + resume, "--size");
  refused("--frames 6 --resume " + shell_quote(out), "it is not a Lueur state file");
  refused("--frames 6 --resume " + shell_quote(dir + "/none"), "--resume: cannot open '" + dir + "/none': No such file");
  // Not a regular file: refused at once, not read until memory runs out (/dev/zero) or forever (a FIFO).
  refused("--frames 6 --resume /dev/zero", "--resume: cannot open '/dev/zero': not a regular file");
  refused("--frames 6 --resume " + shell_quote(dir), "Is a directory");
  refused("--frames 6 --checkpoint -1", "--checkpoint");
  refused("--frames 6 " + shell_quote(std::string(LUEUR_SOURCE_DIR) + "/assets/cornell-apple.obj") + resume,
          "the scene");
  // Cut short, or one byte altered.
  std::string bytes = read_file(state);
  const std::string cut = dir + "/cut.state", altered = dir + "/altered.state";
  {
    FILE* f = std::fopen(cut.c_str(), "wb");
    std::fwrite(bytes.data(), 1, bytes.size() / 2, f);
    std::fclose(f);
    bytes[bytes.size() / 3] ^= 1;
    f = std::fopen(altered.c_str(), "wb");
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
  }
  refused("--frames 6 --resume " + shell_quote(cut), "cut short or altered");
  refused("--frames 6 --resume " + shell_quote(altered), "cut short or altered");
  // A state of the version before (frames sampled otherwise) is refused, not resumed into bytes no render gives.
  const std::string older = dir + "/older.state";
  {
    std::string old_version = read_file(state);
    ASSERT_EQ(old_version.rfind("LUEUR-STATE 4\n", 0), 0u);
    old_version[12] = '3';
    FILE* f = std::fopen(older.c_str(), "wb");
    std::fwrite(old_version.data(), 1, old_version.size(), f);
    std::fclose(f);
  }
  refused("--frames 6 --resume " + shell_quote(older), "it is a state file of another version");
  // Display settings and the frame count may change: the sums do not depend on them.
  const auto more = run_lueur(base + " --frames 9 --exposure 1" + resume);
  EXPECT_EQ(more.exit_code, 0) << more.output;
}

}  // namespace
}  // namespace lueur
