// The window test's fixture: the real viewer started under Xvfb with a state file (--state-file), driven by xdotool,
// waited on through what the state file reports. Shared by test_window.cpp and window_camera_tests.cpp, which build
// one executable that CTest runs inside xvfb-run (tests/CMakeLists.txt).
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_support.h"

namespace lueur::window_test {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

inline std::string run_command(const std::string& command) {
  std::string output;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    ::pclose(pipe);
  }
  while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
  return output;
}

class Window : public ::testing::Test {
 protected:
  /// Options the viewer starts with besides the fixture's own.
  virtual std::vector<std::string> extra_arguments() const { return {}; }
  /// Whether SetUp waits for a first traced frame (a viewer whose scene cannot load has none).
  virtual bool renders_at_start() const { return true; }

  void SetUp() override {
    if (!std::getenv("DISPLAY")) GTEST_FAIL() << "no DISPLAY: CTest runs this test inside xvfb-run";
    ASSERT_FALSE(run_command("command -v xdotool").empty()) << "xdotool is missing (scripts/setup.sh installs it)";
    dir_ = test::make_temp_dir("window");
    state_path_ = dir_ + "/state.json";
    pid_ = ::fork();
    ASSERT_GE(pid_, 0);
    if (pid_ == 0) {
      // Heavy frames (16 L2 rays at 512x512 on a small machine) so that the display must not wait for them.
      std::vector<std::string> arguments = {LUEUR_EXECUTABLE, "--size", "512x512",      "--l1-rays", "4",
                                            "--l2-rays",      "16",     "--state-file", state_path_};
      for (const std::string& extra : extra_arguments()) arguments.push_back(extra);
      std::vector<char*> argv;
      for (std::string& argument : arguments) argv.push_back(argument.data());
      argv.push_back(nullptr);
      ::execv(LUEUR_EXECUTABLE, argv.data());
      std::_Exit(127);
    }
    if (renders_at_start())
      ASSERT_TRUE(wait_for([](const json& s) { return s["frames"].get<int>() >= 1; }))
          << "the viewer never rendered a frame";
    else
      ASSERT_TRUE(wait_for([](const json& s) { return s["display_frames"].get<int>() >= 1; }))
          << "the viewer never drew";
    window_ = run_command("xdotool search --sync --onlyvisible --name '^Lueur$' | head -1");
    ASSERT_FALSE(window_.empty()) << "no window named Lueur";
  }

  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }

  json state() const {
    std::ifstream in(state_path_);
    std::stringstream text;
    text << in.rdbuf();
    json s = json::parse(text.str(), nullptr, false);
    return s.is_discarded() ? json() : s;
  }

  /// Polls the state file until `condition` holds (true), the viewer exits or `seconds` pass (false).
  bool wait_for(const std::function<bool(const json&)>& condition, double seconds = test::kGiveUpSeconds) const {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    while (Clock::now() < end) {
      const json s = state();
      if (s.is_object() && condition(s)) return true;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        ADD_FAILURE() << "the viewer exited (status " << status << ")";
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  /// Waits until the viewer has run `frames` whole frames of its loop (events polled, panel and image drawn) after
  /// this call, so that input sent before the call has been seen. The state file is written at most every 0.1 s,
  /// so the count starts from the first state written after the call.
  void wait_for_viewer_frames(double frames = 1.0) const {
    double before = 0.0, written = 0.0;
    ASSERT_TRUE(wait_for([&](const json& s) {
      before = s["display_frames"].get<double>();
      return true;
    }));
    ASSERT_TRUE(wait_for([&](const json& s) {
      written = s["display_frames"].get<double>();
      return written > before;
    })) << "the viewer stopped drawing";
    ASSERT_TRUE(wait_for([&](const json& s) { return s["display_frames"].get<double>() >= written + frames; }))
        << "the viewer stopped drawing";
  }

  /// Centre of a widget the viewer reports, in window pixels.
  std::pair<int, int> centre_of(const std::string& widget) const {
    const json r = state()["widgets"][widget];
    return {static_cast<int>((r[0].get<float>() + r[2].get<float>()) / 2),
            static_cast<int>((r[1].get<float>() + r[3].get<float>()) / 2)};
  }

  void xdotool(const std::string& arguments) const { run_command("xdotool " + arguments); }

  /// Presses the left button at (x0, y0) and moves to (x1, y1) in steps, keeping it down; the viewer sees each step
  /// in a frame of its own, and the button still down at the end. `before` is xdotool input sent in the same
  /// command as the press, so that both reach the viewer within one of its frames.
  void press_and_drag(int x0, int y0, int x1, int y1, const std::string& before = "") const {
    xdotool(before + "mousemove --window " + window_ + " " + std::to_string(x0) + " " + std::to_string(y0) +
            " mousedown 1");
    wait_for_viewer_frames();
    for (int step = 1; step <= 8; ++step) {
      xdotool("mousemove --window " + window_ + " " + std::to_string(x0 + (x1 - x0) * step / 8) + " " +
              std::to_string(y0 + (y1 - y0) * step / 8));
      wait_for_viewer_frames();
    }
  }

  std::string dir_, state_path_, window_;
  pid_t pid_ = -1;
};

}  // namespace lueur::window_test
