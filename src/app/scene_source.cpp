// Opening a scene: loading or building it, preparing it for tracing, and choosing the view it opens with.
#include "app/scene_source.h"

#include <cstdio>
#include <limits>

#include "scene/default_scene.h"
#include "scene/light_rig.h"
#include "scene/obj_loader.h"

namespace lueur {

SceneOptions scene_options_of(const Settings& settings) {
  SceneOptions options;
  options.smooth_normals = settings.smooth_normals;
  options.light_rig = settings.light_rig;
  options.light_rig_scale = settings.light_rig_scale;
  options.start_view = settings.start_view;
  options.accel = settings.accel;
  return options;
}

namespace {

/// Rays through the scene's accelerator, for find_enclosure.
RayCast accelerator_ray_cast(const TracedScene& traced) {
  return [&traced](const Vec3& origin, const Vec3& dir, bool& front) {
    Ray ray;
    ray.origin = origin;
    ray.dir = dir;
    // The model only: the light rig (a ceiling panel right above the probe) is passed through.
    for (;;) {
      const Hit hit = intersect_closest(traced.accel, ray);
      if (!hit.found()) return std::numeric_limits<float>::infinity();
      if (hit.triangle < traced.scene.rig_begin) {
        front = seen_from_front(traced.scene, hit.triangle, dir);
        return hit.t;
      }
      ray.tmin = hit.t;
    }
  };
}

/// Picks the view the scene opens with, and says why where it matters.
void choose_view(const std::string& label, StartView start, OpenedScene& opened) {
  const bool inside = opened.inside_view && start != StartView::kOutside;
  opened.default_view = inside ? *opened.inside_view : opened.outside_view;
  if (inside)
    opened.notes.push_back(label + " is a closed room: the camera starts inside it (--camera outside, or key O in " +
                           "the window, for the view from outside)");
  else if (opened.inside_view)
    opened.notes.push_back(label + " is a closed room: from outside the camera sees its walls (--camera inside, or " +
                           "key I in the window, for the view from inside)");
  else if (start == StartView::kInside)
    opened.warnings.push_back(label + " is not a closed room: no view from inside, the camera starts outside");
}

}  // namespace

OpenedScene open_scene(const std::string& path, const SceneOptions& options, float aspect, const MemoryBudget& memory,
                       const LoadProgress& progress) {
  OpenedScene opened;
  Scene scene;
  if (path.empty()) {
    scene = make_default_scene();
    if (options.smooth_normals) compute_smooth_normals(scene);
    opened.outside_view = default_scene_camera();
  } else {
    LoadOptions load_options;
    load_options.smooth_normals = options.smooth_normals;
    load_options.memory = memory;
    load_options.light_rig = options.light_rig;
    load_options.light_rig_scale = options.light_rig_scale;
    load_options.threads = options.threads;
    load_options.progress = progress;
    LoadedScene loaded = load_obj(path, load_options);
    scene = std::move(loaded.scene);
    opened.warnings = std::move(loaded.warnings);
    opened.files = std::move(loaded.files);
    opened.stage_times = std::move(loaded.stage_times);
  }
  StageClock clock(progress);
  clock.start(LoadStage::kBvh);
  opened.traced = prepare_scene(std::move(scene), options.accel, clock.reporter());
  clock.stop();
  opened.stage_times.insert(opened.stage_times.end(), clock.times().begin(), clock.times().end());
  if (!path.empty()) {
    const TracedScene& traced = *opened.traced;
    opened.outside_view = frame_box(traced.bounds, 45.0f, aspect);
    if (const std::optional<Enclosure> room = find_enclosure(traced.bounds, accelerator_ray_cast(traced)))
      opened.inside_view = inside_view(traced.bounds, *room);
  }
  choose_view(path.empty() ? std::string("the default scene") : path, options.start_view, opened);
  return opened;
}

std::string describe_stage_times(const std::vector<StageTime>& times) {
  std::string text;
  for (const StageTime& t : times) {
    char line[96];
    std::snprintf(line, sizeof line, "%s%s %.2f s", text.empty() ? "" : ", ", load_stage_name(t.stage), t.seconds);
    text += line;
  }
  return text;
}

}  // namespace lueur
