// Opens what the user asked for: an OBJ file or the embedded default scene, with its default view.
#pragma once

#include "app/options.h"
#include "core/memory_budget.h"
#include "render/traced_scene.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace lueur {

struct OpenedScene {
  std::shared_ptr<const TracedScene> traced;
  CameraSpec default_view;
  std::vector<std::string> warnings;
};

/// Loads (or builds) the scene, applies the normal-smoothing option and prepares it for tracing with `accel`.
/// Throws SceneError for a scene that cannot be used or one too large for `memory`, AccelError for an accelerator
/// this build lacks. `on_stage`, when given, is told each step as it starts (the window shows it while loading).
OpenedScene open_scene(const std::string& path, bool smooth_normals, float aspect, const MemoryBudget& memory,
                       AccelKind accel = AccelKind::kLueur,
                       const std::function<void(const std::string& stage)>& on_stage = {});

}  // namespace lueur
