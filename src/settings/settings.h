// The one settings model: everything a view file, the command line and the panel set (camera, size, passes,
// weights, sampling, reuse, back-end, display, frame counts). What each member means, its range, default, help and
// what a change to it does are rows of the table in settings/setting_table.h, from which the command line, view
// files, image metadata and the panel's limits are all made. Depends on the plain types of the core library below it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "accel/accel_kind.h"
#include "core/camera.h"
#include "passes/render_settings.h"
#include "film/tonemap.h"

namespace lueur {

/// Where a scene's camera starts: auto (inside a closed room, else the view that frames the model from outside),
/// inside a closed room, or outside.
enum class StartView : int { kAuto = 0, kInside = 1, kOutside = 2 };
inline constexpr std::array<std::string_view, 3> kStartViewNames = {"auto", "inside", "outside"};

struct Settings {
  std::optional<CameraSpec> camera;  ///< unset: the scene's default view
  std::optional<Vec3> up;            ///< when set, the up vector of whichever camera is used
  RenderSettings render;             ///< what the tracer needs: size, passes, sampling, reuse, seed
  std::array<float, kPassCount> weights = kReportWeights;
  std::optional<Layer> layer;  ///< what is shown; unset: the weighted combination of the passes
  bool show_noise = false;     ///< show the combined image's estimated noise instead (film/noise_view.h)
  DisplaySettings display;
  bool smooth_normals = true;               ///< smooth normals for files without them
  bool light_rig = true;                    ///< scenes without emitters get the default light rig
  float light_rig_scale = 1.0f;             ///< the rig's radiance factor
  StartView start_view = StartView::kAuto;  ///< which default view a scene opens with (unless `camera` is set)
  AccelKind accel = AccelKind::kLueur;      ///< which acceleration structure traces the rays
  int frames = 64;                          ///< frames a headless render accumulates (a saved view: those shown)
  uint64_t frame_limit = 0;                 ///< the window stops accumulating after this many frames; 0: never
  float time_limit = 0.0f;    ///< seconds of tracing after which a render stops (frame in flight included); 0: never
  float target_noise = 0.0f;  ///< a render stops once the image's estimated relMSE falls below this; 0: never
  bool watch = true;          ///< the window reloads the scene when its files change on disk
  /// A/B comparison: "SETTING=VALUE", the one setting the right side of a split view renders with; empty: none.
  std::string compare;
  float compare_split = 0.5f;  ///< where the split's divider stands, as a share of the image's width from the left
  bool operator==(const Settings&) const = default;
};

/// The camera these settings use, given the scene's default view.
inline CameraSpec camera_of(const Settings& settings, const CameraSpec& scene_default) {
  CameraSpec camera = settings.camera.value_or(scene_default);
  if (settings.up) camera.up = *settings.up;
  return camera;
}

}  // namespace lueur
