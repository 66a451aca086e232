#include "app/scene_source.h"

#include "scene/default_scene.h"
#include "scene/obj_loader.h"

namespace lueur {

OpenedScene open_scene(const std::string& path, bool smooth_normals, float aspect, const MemoryBudget& memory,
                       AccelKind accel, const std::function<void(const std::string& stage)>& on_stage) {
  const auto stage = [&](const std::string& what) {
    if (on_stage) on_stage(what);
  };
  OpenedScene opened;
  Scene scene;
  if (path.empty()) {
    scene = make_default_scene();
    if (smooth_normals) compute_smooth_normals(scene);
    opened.default_view = default_scene_camera();
  } else {
    stage("reading " + path);
    LoadOptions load_options;
    load_options.smooth_normals = smooth_normals;
    load_options.memory = memory;
    LoadedScene loaded = load_obj(path, load_options);
    scene = std::move(loaded.scene);
    opened.warnings = std::move(loaded.warnings);
    opened.default_view = frame_box(scene.bounds(), 45.0f, aspect);
  }
  stage("building the BVH of " + std::to_string(scene.triangles.size()) + " triangles");
  opened.traced = prepare_scene(std::move(scene), accel);
  return opened;
}

}  // namespace lueur
