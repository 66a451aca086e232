// Writing the scene as it is rendered (see scene_export.h).
#include "app/scene_export.h"

#include <cstdio>

#include "app/scene_source.h"
#include "core/memory_budget.h"
#include "render/indirect_light.h"
#include "scene/obj_writer.h"
#include "settings/setting_table.h"

namespace lueur {

void export_scene(const AppOptions& options) {
  const RenderSettings& render = options.settings.render;
  const float aspect = static_cast<float>(render.width) / static_cast<float>(render.height);
  const OpenedScene opened = open_scene(options.scene_path, scene_options_of(options.settings), aspect,
                                        available_memory());
  for (const std::string& w : opened.warnings) std::fprintf(stderr, "lueur: warning: %s\n", w.c_str());
  write_obj(opened.traced->scene, options.export_scene);
  std::printf("%s\n", options.export_scene.c_str());
  // The export has no camera, and as a file whose emitters are its own it gets no rig: its bounds (which frame the
  // view and size the automatic AO radius) take the rig in. The options that render it as this scene renders.
  Settings view = options.settings;
  view.camera = camera_of(options.settings, opened.default_view);
  view.render.ao_radius = ambient_occlusion_radius(*opened.traced, options.settings.render);
  std::fprintf(stderr, "lueur: render it as this scene renders with --camera \"%s\" --ao-radius %s\n",
               setting_text(view, "camera").value_or("").c_str(), setting_text(view, "ao-radius").value_or("").c_str());
}

}  // namespace lueur
