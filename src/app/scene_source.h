// Opens what the user asked for: an OBJ file or the embedded default scene, with its default view.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/options.h"
#include "core/file_watch.h"
#include "core/memory_budget.h"
#include "integrator/traced_scene.h"
#include "settings/settings.h"

namespace lueur {

struct OpenedScene {
  std::shared_ptr<const TracedScene> traced;
  CameraSpec default_view;                ///< the view the scene opens with (per StartView)
  CameraSpec outside_view;                ///< framing the model from outside
  std::optional<CameraSpec> inside_view;  ///< from inside, when the model is a closed room
  std::vector<std::string> warnings;
  std::vector<std::string> notes;  ///< what a user should know about the view (a closed room, and how to leave it)
  std::vector<WatchedFile> files;  ///< the files it was read from, stamped as read (none for the default scene)
};

/// What shapes the opened scene: the settings the table marks kReload, and where its camera starts.
struct SceneOptions {
  bool smooth_normals = true;
  bool light_rig = true;
  float light_rig_scale = 1.0f;
  StartView start_view = StartView::kAuto;
  AccelKind accel = AccelKind::kLueur;
};
SceneOptions scene_options_of(const Settings& settings);

/// Loads (or builds) the scene, applies the normal-smoothing and light-rig options and prepares it for tracing.
/// A model that is a closed room (find_enclosure, probed with the accelerator) also gets the view from inside,
/// which becomes its default view unless `options.start_view` says outside. Throws SceneError for a scene that
/// cannot be used or one too large for `memory`, AccelError for an accelerator this build lacks. `on_stage`, when
/// given, is told each step as it starts (the window shows it while loading).
OpenedScene open_scene(const std::string& path, const SceneOptions& options, float aspect, const MemoryBudget& memory,
                       const std::function<void(const std::string& stage)>& on_stage = {});

}  // namespace lueur
