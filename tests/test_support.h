// Helpers shared by the test suites: temporary directories, running the lueur executable, file reading.
#pragma once

#include <string>

namespace lueur::test {

/// A fresh empty directory under the system temp dir, removed at exit of the test process.
std::string make_temp_dir(const std::string& tag);

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `lueur` (the built executable) with the given argument string through the shell.
CommandResult run_lueur(const std::string& arguments);

std::string read_file(const std::string& path);
bool file_exists(const std::string& path);

/// Path of ../shared/scenes/<relative>; empty when the shared scenes are not beside this checkout.
std::string shared_scene(const std::string& relative);

}  // namespace lueur::test
