// The headless loading line on a terminal: the stages with their share and time, redrawn in place while a stage
// says nothing, and cleared before the summary. Checked on the class with stderr sent to a file, and on lueur itself
// run under a pseudo-terminal.
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "app/load_progress_line.h"
#include "test_support.h"

namespace lueur {
namespace {

/// What the line printed for `stage_name`, each drawing's time in seconds, in order.
std::vector<double> drawn_times(const std::string& output, const std::string& stage_name) {
  std::vector<double> times;
  const std::regex drawing("\rlueur: loading [^:]*: " + stage_name + "( +[0-9]+%)? \\(([0-9.]+) s\\)\033\\[K");
  for (auto it = std::sregex_iterator(output.begin(), output.end(), drawing); it != std::sregex_iterator(); ++it)
    times.push_back(std::stod((*it)[2].str()));
  return times;
}

TEST(LoadProgressLine, ASilentStageIsRedrawnWithTheTimeGoingOn) {
  const std::string path = test::make_temp_dir("progress-line") + "/stderr.txt";
  std::fflush(stderr);
  const int saved = dup(STDERR_FILENO);
  FILE* file = std::fopen(path.c_str(), "w");
  ASSERT_NE(file, nullptr);
  dup2(fileno(file), STDERR_FILENO);
  {
    LoadProgressLine line("scene.obj", true);
    const LoadProgress progress = line.callback();
    ASSERT_TRUE(progress);
    progress(LoadStage::kConvert, -1.0);  // then nothing for 1.5 s
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    progress(LoadStage::kBvh, 0.5);
    line.finish();
    std::this_thread::sleep_for(std::chrono::milliseconds(400));  // nothing may be drawn after finish()
  }
  std::fflush(stderr);
  dup2(saved, STDERR_FILENO);
  close(saved);
  std::fclose(file);
  const std::string output = test::read_file(path);

  const std::vector<double> converting = drawn_times(output, "converting");
  ASSERT_GE(converting.size(), 3u) << "drawn when the stage began, then again while it said nothing:\n" << output;
  EXPECT_LT(converting.front(), 0.2);
  EXPECT_GE(converting.back(), 0.9);
  for (size_t i = 1; i < converting.size(); ++i) EXPECT_GE(converting[i], converting[i - 1]);
  EXPECT_EQ(drawn_times(output, "building the BVH").size(), 1u) << output;
  EXPECT_NE(output.find("building the BVH  50% ("), std::string::npos) << output;
  ASSERT_GE(output.size(), 4u);
  EXPECT_EQ(output.substr(output.size() - 4), "\r\033[K") << "cleared last, and nothing after";
}

TEST(LoadProgressLine, OffATerminalNothingIsDrawn) {
  LoadProgressLine line("scene.obj", false);
  EXPECT_FALSE(line.callback());
}

/// Runs `argv` with its stdin, stdout and stderr on a new pseudo-terminal; returns all it wrote there.
std::string run_on_a_terminal(const std::vector<std::string>& argv, int& status) {
  int terminal = -1;
  const pid_t pid = forkpty(&terminal, nullptr, nullptr, nullptr);
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  std::string output;
  char buffer[4096];
  for (ssize_t n; (n = read(terminal, buffer, sizeof buffer)) > 0;) output.append(buffer, static_cast<size_t>(n));
  close(terminal);
  waitpid(pid, &status, 0);
  return output;
}

TEST(LoadProgressLine, LueurOnATerminalShowsEachStageThenTheSummary) {
  // A 100 x 100 grid of quads without normals: every stage runs, normals and BVH included.
  const std::string dir = test::make_temp_dir("progress-lueur");
  std::string obj = "mtllib grid.mtl\nusemtl light\nv -1 2 -1\nv 1 2 -1\nv 1 2 1\nv -1 2 1\nf 1 4 3 2\nusemtl ground\n";
  for (int z = 0; z <= 100; ++z)
    for (int x = 0; x <= 100; ++x)
      obj += "v " + std::to_string(x / 50.0 - 1.0) + " " + std::to_string(0.05 * ((x * 7 + z * 3) % 5)) + " " +
             std::to_string(z / 50.0 - 1.0) + "\n";
  for (int z = 0; z < 100; ++z)
    for (int x = 0; x < 100; ++x) {
      const int a = 5 + z * 101 + x;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 101) + " " + std::to_string(a + 102) + " " +
             std::to_string(a + 1) + "\n";
    }
  std::ofstream(dir + "/grid.obj") << obj;
  std::ofstream(dir + "/grid.mtl") << "newmtl ground\nKd 0.5 0.5 0.5\nnewmtl light\nKe 5 5 5\n";
  int status = 0;
  const std::string output = run_on_a_terminal(
      {LUEUR_EXECUTABLE, "--headless", dir + "/grid.obj", "--frames", "1", "--size", "16x16", "--out", dir + "/x.pfm"},
      status);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
  for (const char* stage : {"reading", "parsing and checking", "converting", "computing normals", "building the BVH"})
    EXPECT_FALSE(drawn_times(output, stage).empty()) << stage << " was never drawn:\n" << output;
  const size_t summary = output.find("lueur: loading stages: reading ");
  ASSERT_NE(summary, std::string::npos) << output;
  EXPECT_NE(output.rfind("\r\033[K", summary), std::string::npos) << "the line is cleared before the summary";
  EXPECT_EQ(output.find("\rlueur: loading ", summary), std::string::npos) << "and not drawn after it";
}

}  // namespace
}  // namespace lueur
