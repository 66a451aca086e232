// The command line, parsed into plain settings for the headless mode (and, later, the window's first state).
#pragma once

#include "render/camera.h"
#include "render/settings.h"
#include "render/tonemap.h"

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

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
  std::optional<Layer> view;  ///< unset: the weighted combination of the passes
  std::string export_default_scene;  ///< when set: write the embedded scene as OBJ + MTL there and exit
};

/// Parses argv. Returns nullopt when --help or --version printed something and the program should exit 0.
/// Throws UsageError with a one-line message for anything malformed.
std::optional<AppOptions> parse_command_line(int argc, char** argv);

/// The settings as command-line options, stored in every saved image so that it can be reproduced.
std::string describe_options(const AppOptions& options);

}  // namespace lueur
