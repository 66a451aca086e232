// No lost output: lueur is killed (SIGKILL) in the middle of writing a large EXR, and the file on disk is then
// either the old one, byte for byte, or the complete new one; never a partial file, and nothing left beside it
// that could be taken for output. LUEUR_TEST_PAUSE_MID_WRITE (see core/atomic_file.h) makes the kill land
// mid-write deterministically; a second test kills at random moments without it. Ctrl-C (SIGINT) or SIGTERM during
// a headless render loses nothing either: the frames done are written, with the state that --resume goes on from.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <set>
#include <thread>

#include "core/atomic_file.h"
#include "test_support.h"

extern char** environ;

namespace lueur {
namespace {

namespace fs = std::filesystem;

/// A running lueur with its stdout and stderr on one pipe.
class Child {
 public:
  Child(const std::vector<std::string>& arguments, const std::vector<std::string>& extra_environment) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
    posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
    std::vector<std::string> storage{LUEUR_EXECUTABLE};
    storage.insert(storage.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& s : storage) argv.push_back(s.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_storage(extra_environment);
    for (char** e = environ; *e; ++e) env_storage.emplace_back(*e);
    std::vector<char*> envp;
    for (std::string& s : env_storage) envp.push_back(s.data());
    envp.push_back(nullptr);
    // SIGINT and SIGTERM with their default actions, whatever this process inherited: a test run started in the
    // background by a shell without job control ignores SIGINT, and lueur, rightly, would keep ignoring it.
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    const int error = ::posix_spawn(&pid_, LUEUR_EXECUTABLE, &actions, &attributes, argv.data(), envp.data());
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[1]);
    output_fd_ = fds[0];
    if (error != 0) throw std::runtime_error("posix_spawn failed");
  }
  ~Child() {
    if (pid_ > 0) kill_now();
    ::close(output_fd_);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  /// Reads output until `needle` appears (true), or the process closes its output or `seconds` pass (false).
  bool wait_for_output(const std::string& needle, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (output_.find(needle) == std::string::npos) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return false;
      pollfd p{output_fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
      char buffer[4096];
      const ssize_t n = ::read(output_fd_, buffer, sizeof buffer);
      if (n <= 0) return false;
      output_.append(buffer, static_cast<size_t>(n));
    }
    return true;
  }
  /// SIGKILL and reap; returns the signal number that ended it (0 if it had exited by itself).
  int kill_now() {
    ::kill(pid_, SIGKILL);
    return reap();
  }
  /// Waits for the process to end; returns its exit status, or 128 + the signal.
  int reap() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  pid_t pid() const { return pid_; }
  const std::string& output() const { return output_; }

 private:
  pid_t pid_ = -1;
  int output_fd_ = -1;
  std::string output_;
};

std::set<std::string> entries(const std::string& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

/// Whether the writer can use an unnamed temporary file in `dir` (then a kill leaves nothing at all).
bool supports_unnamed_temp(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0600);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

/// A large multi-layer EXR render (seed chooses the content) that is quick to trace.
std::vector<std::string> exr_render(const std::string& out, int seed) {
  return {"--headless",         "--size", "384x384",   "--frames", "1",         "--passes", "le,l1,l2,ao",
          "--l1-rays",          "1",      "--l2-rays", "1",        "--ao-rays", "1",        "--seed",
          std::to_string(seed), "--out",  out};
}

constexpr const char* kPause = "LUEUR_TEST_PAUSE_MID_WRITE=600";
constexpr double kStartupSeconds = 240.0;  // sanitizer builds render slowly

class NoLostOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("no-lost-output");
    out_ = dir_ + "/image.exr";
    // The complete new file, rendered undisturbed elsewhere: rendering is deterministic.
    reference_dir_ = test::make_temp_dir("no-lost-output-reference");
    Child reference(exr_render(reference_dir_ + "/image.exr", 2), {});
    ASSERT_EQ(reference.reap(), 0);
    new_bytes_ = test::read_file(reference_dir_ + "/image.exr");
    ASSERT_GT(new_bytes_.size(), 1000000u) << "the EXR should be large enough to take a while to write";
  }

  /// Nothing but the output itself may be in the directory; where O_TMPFILE is missing, the writer's hidden
  /// temporary file is tolerated (it cannot be mistaken for output), and nothing else.
  void expect_only_output_in_dir(pid_t killed) {
    std::set<std::string> names = entries(dir_);
    names.erase("image.exr");
    if (!supports_unnamed_temp(dir_))
      names.erase(fs::path(named_temp_path(out_, static_cast<long>(killed))).filename().string());
    EXPECT_TRUE(names.empty()) << "left behind: " << *names.begin();
  }

  std::string dir_, out_, reference_dir_, new_bytes_;
};

TEST_F(NoLostOutput, KilledMidWriteKeepsTheOldFile) {
  Child first(exr_render(out_, 1), {});
  ASSERT_EQ(first.reap(), 0) << first.output();
  const std::string old_bytes = test::read_file(out_);
  ASSERT_NE(old_bytes, new_bytes_);

  Child second(exr_render(out_, 2), {kPause});
  ASSERT_TRUE(second.wait_for_output("paused mid-write of '" + out_ + "'", kStartupSeconds)) << second.output();
  const pid_t pid = second.pid();
  EXPECT_EQ(second.kill_now(), 128 + SIGKILL);
  EXPECT_EQ(test::read_file(out_), old_bytes) << "the old file must survive a kill mid-write";
  expect_only_output_in_dir(pid);

  // Run again, undisturbed: the complete new file replaces the old one.
  Child third(exr_render(out_, 2), {});
  ASSERT_EQ(third.reap(), 0) << third.output();
  EXPECT_EQ(test::read_file(out_), new_bytes_);
  EXPECT_EQ(entries(dir_), std::set<std::string>{"image.exr"});
}

TEST_F(NoLostOutput, TheNamedFallbackKilledMidWriteKeepsTheOldFile) {
  // Where the filesystem has no O_TMPFILE, the bytes go to a hidden named file first.
  constexpr const char* kNoTmpfile = "LUEUR_TEST_NO_TMPFILE=1";
  Child first(exr_render(out_, 1), {kNoTmpfile});
  ASSERT_EQ(first.reap(), 0) << first.output();
  const std::string old_bytes = test::read_file(out_);
  EXPECT_EQ(entries(dir_), std::set<std::string>{"image.exr"}) << "the named temporary file was not renamed";

  Child second(exr_render(out_, 2), {kPause, kNoTmpfile});
  ASSERT_TRUE(second.wait_for_output("paused mid-write of '" + out_ + "'", kStartupSeconds)) << second.output();
  const pid_t pid = second.pid();
  const std::string temp = named_temp_path(out_, static_cast<long>(pid));
  EXPECT_TRUE(test::file_exists(temp)) << "the fallback should be writing " << temp;
  EXPECT_EQ(second.kill_now(), 128 + SIGKILL);
  EXPECT_EQ(test::read_file(out_), old_bytes) << "the old file must survive a kill mid-write";
  std::set<std::string> left = entries(dir_);
  left.erase("image.exr");
  left.erase(fs::path(temp).filename().string());  // hidden, and never taken for output
  EXPECT_TRUE(left.empty()) << "left behind: " << *left.begin();

  Child third(exr_render(out_, 2), {kNoTmpfile});
  ASSERT_EQ(third.reap(), 0) << third.output();
  EXPECT_EQ(test::read_file(out_), new_bytes_);
}

TEST_F(NoLostOutput, KilledMidWriteWithNoOldFileLeavesNothing) {
  Child child(exr_render(out_, 2), {kPause});
  ASSERT_TRUE(child.wait_for_output("paused mid-write", kStartupSeconds)) << child.output();
  const pid_t pid = child.pid();
  child.kill_now();
  EXPECT_FALSE(test::file_exists(out_));
  expect_only_output_in_dir(pid);
}

TEST_F(NoLostOutput, KilledAtRandomMomentsAlwaysOldOrCompleteNew) {
  Child first(exr_render(out_, 1), {});
  ASSERT_EQ(first.reap(), 0);
  const std::string old_bytes = test::read_file(out_);
  // How long an undisturbed run takes, to spread the kills over it (most land in rendering, some in writing).
  const auto start = std::chrono::steady_clock::now();
  Child timed(exr_render(dir_ + "/timed.exr", 2), {});
  ASSERT_EQ(timed.reap(), 0);
  const double run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fs::remove(dir_ + "/timed.exr");

  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> when(0.5 * run_seconds, 1.1 * run_seconds);
  int old_seen = 0, new_seen = 0;
  for (int attempt = 0; attempt < 6; ++attempt) {
    Child child(exr_render(out_, 2), {});
    std::this_thread::sleep_for(std::chrono::duration<double>(when(rng)));
    const pid_t pid = child.pid();
    child.kill_now();
    const std::string bytes = test::read_file(out_);
    if (bytes == old_bytes) {
      ++old_seen;
    } else {
      ASSERT_EQ(bytes, new_bytes_) << "attempt " << attempt << ": a partial or foreign file";
      ++new_seen;
      // Put the old file back for the next attempt.
      Child restore(exr_render(out_, 1), {});
      ASSERT_EQ(restore.reap(), 0);
    }
    expect_only_output_in_dir(pid);
  }
  std::printf("killed 6 runs: %d left the old file, %d the complete new one\n", old_seen, new_seen);
}

class InterruptedRender : public ::testing::TestWithParam<int> {};

// The first SIGINT or SIGTERM stops a headless render after the frame in flight: the image holds the frames done,
// byte for byte what an uninterrupted render of that many frames writes, the state beside it resumes to the bytes
// of an uninterrupted longer render, and the exit status is 128 + the signal. (Before, the signal ended lueur at
// once and every frame traced was lost.)
TEST_P(InterruptedRender, WritesTheFramesDoneAndTheStateToResumeFrom) {
  const int signal_number = GetParam();
  const std::string dir = test::make_temp_dir(std::string("interrupted-") + (signal_number == SIGINT ? "int" : "term"));
  const std::string out = dir + "/image.pfm", state = out + ".lueur-state";
  const std::string size = "32x24";
  Child render({"--headless", "--size", size, "--frames", "1000000", "--checkpoint", "100000", "--out", out}, {});
  // The progress line comes from inside the frame loop, where the signals are caught.
  ASSERT_TRUE(render.wait_for_output("lueur: frame ", kStartupSeconds)) << render.output();
  ::kill(render.pid(), signal_number);
  ASSERT_TRUE(render.wait_for_output(" (a second one ends lueur at once)\n", kStartupSeconds)) << render.output();
  render.wait_for_output("\n" + out + "\n", kStartupSeconds);  // the path, printed last
  EXPECT_EQ(render.reap(), 128 + signal_number) << render.output();
  const std::string& said = render.output();
  const size_t at = said.find("stopped after ");
  ASSERT_NE(at, std::string::npos) << said;
  const int frames = std::stoi(said.substr(at + 14));
  ASSERT_GT(frames, 0) << said;
  EXPECT_EQ(entries(dir), (std::set<std::string>{"image.pfm", "image.pfm.lueur-state"}));

  const std::string base = "--headless --size " + size + " --out ";
  const std::string whole = dir + "/whole.pfm";
  const auto uninterrupted = test::run_lueur(base + whole + " --frames " + std::to_string(frames));
  ASSERT_EQ(uninterrupted.exit_code, 0) << uninterrupted.output;
  EXPECT_EQ(test::read_file(out), test::read_file(whole)) << "the interrupted image is not its frames' image";

  const std::string more = std::to_string(frames + 3);
  const auto resumed = test::run_lueur(base + out + " --frames " + more + " --resume " + state);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const auto longer = test::run_lueur(base + whole + " --frames " + more);
  ASSERT_EQ(longer.exit_code, 0) << longer.output;
  EXPECT_EQ(test::read_file(out), test::read_file(whole)) << "the resumed image differs from the uninterrupted one";
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptedRender, ::testing::Values(SIGINT, SIGTERM),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return std::string(p.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

}  // namespace
}  // namespace lueur
