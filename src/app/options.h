// The command line: the settings (settings/settings.h, one row each in the settings table) and, beside them, what
// only this run of the program needs: paths, headless or window, GL context, threads.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "display/headless_context.h"
#include "settings/settings.h"

namespace lueur {

/// A bad option: main prints it on one line and exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct AppOptions {
  Settings settings;       ///< what is rendered and how it is shown: the view file's contents, then the options
  std::string scene_path;  ///< empty: the embedded default scene
  bool headless = false;
  std::string out_path;
  int threads = 0;                    ///< 0: every hardware thread
  HeadlessGl gl = HeadlessGl::kNone;  ///< headless PNG through the GL display path (egl, osmesa, auto) or the CPU
  bool ui = false;                    ///< draw the panel into the headless screenshot
  std::string view_file;              ///< --view-file: a view saved by the window
  std::string export_default_scene;   ///< when set: write the embedded scene as OBJ + MTL there and exit
  std::string export_scene;  ///< when set: write the scene as it is rendered (rig, normals) as OBJ + MTL there and exit
  std::string state_file;             ///< --state-file: the window writes its view and statistics there (for tests)
  double checkpoint_seconds = 0.0;    ///< headless: write the image so far and the resume state at this interval
  std::string resume_path;            ///< headless: go on from this resume state (written by --checkpoint)
};

/// Which program parses: its name and the first line of its --help.
struct ProgramName {
  const char* name = "lueur";
  const char* description = "Lueur: a progressive CPU ray tracer of direct (L1) and one-bounce indirect (L2) light";
};

/// Parses argv. Returns nullopt when --help or --version printed something and the program should exit 0.
/// Throws UsageError with a one-line message for anything malformed.
std::optional<AppOptions> parse_command_line(int argc, char** argv, const ProgramName& program = {});

/// The command that renders this image again: the scene and the settings as options, stored in every saved image.
std::string describe_options(const std::string& scene_path, const Settings& settings);

}  // namespace lueur
