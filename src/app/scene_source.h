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
#include "scene/load_stages.h"
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
  std::vector<StageTime> stage_times;  ///< how long each stage of opening it took, the BVH's included
};

/// What shapes the opened scene: the settings the table marks kReload, and where its camera starts.
struct SceneOptions {
  bool smooth_normals = true;
  bool light_rig = true;
  float light_rig_scale = 1.0f;
  StartView start_view = StartView::kAuto;
  AccelKind accel = AccelKind::kLueur;
  unsigned threads = 0;  ///< threads that read the file; 0: every core
};
SceneOptions scene_options_of(const Settings& settings);

/// Loads (or builds) the scene, applies the normal-smoothing and light-rig options and prepares it for tracing.
/// A model that is a closed room (find_enclosure, probed with the accelerator) also gets the view from inside,
/// which becomes its default view unless `options.start_view` says outside. Throws SceneError for a scene that
/// cannot be used or one too large for `memory`, AccelError for an accelerator this build lacks. `progress`, when
/// given, is told each stage and its share done as it goes (the window and the headless progress line show them).
OpenedScene open_scene(const std::string& path, const SceneOptions& options, float aspect, const MemoryBudget& memory,
                       const LoadProgress& progress = {});

/// "reading 0.05 s, parsing and checking 0.61 s, ...": the stages' times, for the summary line.
std::string describe_stage_times(const std::vector<StageTime>& times);

}  // namespace lueur
