// A view: the camera and every setting that made an image (render settings, pass weights, display transform, the
// layer shown). The window saves it as JSON and `lueur --headless --view-file` renders it again exactly.
// Depends on the render layer; JSON through nlohmann-json.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "render/camera.h"
#include "render/settings.h"
#include "render/tonemap.h"

namespace lueur {

struct ViewState {
  std::optional<CameraSpec> camera;  ///< unset: the scene's default view
  RenderSettings render;
  std::array<float, kPassCount> weights = kReportWeights;
  std::optional<Layer> layer;  ///< unset: the weighted combination of the passes
  DisplaySettings display;
  bool smooth_normals = true;
  uint64_t frame_limit = 0;  ///< 0: no limit
  uint64_t frames = 0;       ///< frames accumulated when the view was saved (a headless render repeats them)
  bool operator==(const ViewState&) const = default;
};

/// A view file that cannot be used; the message names the field.
struct ViewFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string view_to_json(const ViewState& view);
/// Parses a view; fields that are absent keep the values of `defaults`. Throws ViewFileError.
ViewState view_from_json(const std::string& text, const ViewState& defaults = {});

/// Writes atomically (IoError) / reads (IoError for a missing file, ViewFileError for bad contents).
void save_view_file(const std::string& path, const ViewState& view);
ViewState load_view_file(const std::string& path, const ViewState& defaults = {});

}  // namespace lueur
