// lueur-mpi, as ranks on this machine (mpirun --oversubscribe): the same bytes as `lueur --headless` for 1 to 4
// ranks and any threads per rank, in every format; a rank killed mid-render ends the job with one line from rank 0
// and no partial file; the last checkpoint resumes, on another number of ranks, to the uninterrupted bytes.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_support.h"

namespace lueur {
namespace {

using test::CommandResult;
using test::file_exists;
using test::make_temp_dir;
using test::read_file;
using test::shell_quote;

/// mpirun as root (CI runs as root). In a sanitizer build, leak checking is off for the lueur-mpi processes: Open MPI
/// leaves allocations of its plugins behind at MPI_Finalize, after unloading them, so that no suppression can name
/// them. Everything else stays checked, and the code lueur-mpi shares with lueur is leak-checked in lueur's tests.
const std::string kMpiEnvironment =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\"";

std::string mpirun(int ranks, const std::string& arguments) {
  return "mpirun --oversubscribe -n " + std::to_string(ranks) + " " + shell_quote(LUEUR_MPI_EXECUTABLE) + " " +
         arguments;
}

CommandResult run_shell(const std::string& script) {
  return test::run_program("sh", "-c " + shell_quote(kMpiEnvironment + " " + script));
}

TEST(Mpi, SameBytesForOneToFourRanksAndTheSingleBinary) {
  const std::string dir = make_temp_dir("mpi_bytes");
  // 13 frames: not a power of two, so the last round ends between two of them.
  const std::string base = "--headless --size 40x28 --frames 13 --l1-rays 4 --l2-rays 4";
  struct Case {
    const char* options;
    const char* file;
  };
  const Case cases[] = {{"", "plain.pfm"},
                        {"--passes le,l1,l2,ao,ln --ln-rays 2 --sampler sobol", "passes.exr"},
                        {"--compare lights=uniform", "split.png"}};
  for (const Case& c : cases) {
    const std::string single = dir + "/single-" + c.file;
    const auto one = test::run_lueur(base + " " + c.options + " --threads 2 --out " + shell_quote(single));
    ASSERT_EQ(one.exit_code, 0) << one.output;
    for (int ranks = 1; ranks <= 4; ++ranks) {
      const std::string out = dir + "/" + std::to_string(ranks) + "-" + c.file;
      const int threads = ranks % 2 == 0 ? 1 : 2;
      const auto r = run_shell(mpirun(
          ranks, base + " " + c.options + " --threads " + std::to_string(threads) + " --out " + shell_quote(out)));
      ASSERT_EQ(r.exit_code, 0) << r.output;
      EXPECT_NE(r.output.find("on " + std::to_string(ranks) + " rank"), std::string::npos) << r.output;
      EXPECT_EQ(read_file(out), read_file(single)) << c.file << " on " << ranks << " ranks differs from lueur's";
    }
  }
}

TEST(Mpi, AKilledRankEndsTheJobCleanlyAndItsCheckpointResumesOnOtherRanks) {
  const std::string dir = make_temp_dir("mpi_kill");
  const std::string base = "--headless --size 32x24 --frames 3000 --l1-rays 2 --l2-rays 2";
  const std::string whole = dir + "/whole.pfm", part = dir + "/part.pfm", state = part + ".lueur-state";
  ASSERT_EQ(test::run_lueur(base + " --out " + shell_quote(whole)).exit_code, 0);

  // Rank 1 is killed (SIGKILL) once the first checkpoint is written. 3000 frames keep the job running well past that
  // on a fast machine; the wait gives up if the job ends without a checkpoint (the checks below then fail, no hang).
  const std::string script =
      mpirun(3, base + " --threads 1 --checkpoint 0.05 --out " + shell_quote(part)) + " & job=$!; " + "while [ ! -f " +
      shell_quote(state) + " ] && kill -0 $job 2>/dev/null; do sleep 0.02; done; sleep 0.05; " +
      "for p in $(pgrep -f " + shell_quote(part) + "); do " +
      "  if tr '\\0' '\\n' < /proc/$p/environ 2>/dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then kill -9 $p; fi; " +
      "done; wait $job";
  const auto killed = run_shell(script);
  EXPECT_NE(killed.exit_code, 0) << killed.output;
  EXPECT_NE(killed.output.find("lueur-mpi: error: the job was stopped (a rank died, or it was cancelled); go on from "
                               "the last checkpoint with --resume"),
            std::string::npos)
      << killed.output;
  // Nothing half-written: only the last checkpoint's image and state are there.
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"part.pfm", "part.pfm.lueur-state", "whole.pfm"}));
  EXPECT_EQ(read_file(part).size(), read_file(whole).size());

  const auto resumed =
      run_shell(mpirun(2, base + " --threads 1 --out " + shell_quote(part) + " --resume " + shell_quote(state)));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  EXPECT_EQ(read_file(part), read_file(whole)) << "the resumed image differs from the uninterrupted one";
}

TEST(Mpi, BadOptionsAndFilesEndEveryRankWithOneLineFromRankZero) {
  const std::string dir = make_temp_dir("mpi_errors");
  const auto expect_error = [&](const std::string& arguments, const std::string& message) {
    const auto r = run_shell(mpirun(3, arguments));
    EXPECT_NE(r.exit_code, 0) << arguments;
    size_t lines = 0;
    for (size_t at = r.output.find("lueur-mpi: error:"); at != std::string::npos;
         at = r.output.find("lueur-mpi: error:", at + 1))
      ++lines;
    EXPECT_EQ(lines, 1u) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  };
  expect_error("--headless --out " + shell_quote(dir + "/x.pfm") + " --reuse cache",
               "--reuse cache: each frame reads what the frames before it left");
  expect_error("--headless --out " + shell_quote(dir + "/x.pfm") + " --reuse average", "--reuse average");
  expect_error(shell_quote(dir + "/none.obj") + " --headless --out " + shell_quote(dir + "/x.pfm"), "none.obj");
  expect_error("--headless --out " + shell_quote(dir + "/no/x.pfm"), "no directory");
  expect_error("--headless --out " + shell_quote(dir + "/x.pfm") + " --l1-rays -3", "--l1-rays");
  expect_error("--headless", "needs --out");
  EXPECT_FALSE(file_exists(dir + "/x.pfm"));
}

TEST(Mpi, HelpNamesLueurMpiOnceFromRankZero) {
  const auto r = run_shell(mpirun(2, "--help"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const size_t usage = r.output.find("Usage: lueur-mpi ");
  ASSERT_NE(usage, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Usage:", usage + 1), std::string::npos) << "help printed by more than one rank";
  EXPECT_NE(r.output.find("--reuse"), std::string::npos) << "the settings' options are listed";
}

}  // namespace
}  // namespace lueur
