#include "test_support.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace lueur::test {

std::string make_temp_dir(const std::string& tag) {
  namespace fs = std::filesystem;
  const fs::path base = fs::temp_directory_path() / ("lueur-test-" + tag + "-" + std::to_string(::getpid()));
  std::error_code ignored;
  fs::remove_all(base, ignored);
  fs::create_directories(base);
  return base.string();
}

CommandResult run_lueur(const std::string& arguments) {
  CommandResult result;
  const std::string command = std::string("'") + LUEUR_EXECUTABLE + "' " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

bool file_exists(const std::string& path) { return std::filesystem::exists(path); }

std::string shared_scene(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(LUEUR_SHARED_SCENES) / relative;
  return std::filesystem::exists(path) ? path.string() : std::string();
}

}  // namespace lueur::test
