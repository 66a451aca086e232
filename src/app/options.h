// The command line, parsed into plain settings for the headless mode (and, later, the window's first state).
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "display/headless_context.h"
#include "render/camera.h"
#include "render/settings.h"
#include "render/tonemap.h"
#include "render/view_state.h"

namespace lueur {

/// A bad option: main prints it on one line and exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct AppOptions {
  std::string scene_path;  ///< empty: the embedded default scene
  bool headless = false;
  std::string out_path;
  int frames = 64;
  int threads = 0;  ///< 0: every hardware thread
  bool smooth_normals = true;
  AccelKind accel = AccelKind::kLueur;  ///< which acceleration structure traces the rays
  RenderSettings render;
  std::array<float, kPassCount> weights = kReportWeights;
  DisplaySettings display;
  std::optional<CameraSpec> camera;  ///< unset: the scene's default view
  std::optional<Vec3> up;
  std::optional<Layer> view;          ///< unset: the weighted combination of the passes
  std::string export_default_scene;   ///< when set: write the embedded scene as OBJ + MTL there and exit
  HeadlessGl gl = HeadlessGl::kNone;  ///< headless PNG through the GL display path (egl, osmesa, auto) or the CPU
  bool ui = false;                    ///< draw the panel into the headless screenshot
  std::string view_file;              ///< --view-file: a view saved by the window
  uint64_t frame_limit = 0;           ///< the window's frame limit (0: none)
  std::string state_file;             ///< --state-file: the window writes its view and statistics there (for tests)
};

/// The view these options describe (camera unset when the scene's default is meant).
ViewState view_from_options(const AppOptions& options);
/// Sets the options from a view.
void apply_view(const ViewState& view, AppOptions& options);

/// Parses argv. Returns nullopt when --help or --version printed something and the program should exit 0.
/// Throws UsageError with a one-line message for anything malformed.
std::optional<AppOptions> parse_command_line(int argc, char** argv);

/// The settings as command-line options, stored in every saved image so that it can be reproduced.
std::string describe_options(const AppOptions& options);

}  // namespace lueur
