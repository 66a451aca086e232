// Writing the scene as it is rendered (see scene_export.h).
#include "app/scene_export.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "app/render_output.h"
#include "app/scene_source.h"
#include "core/atomic_file.h"
#include "core/memory_budget.h"
#include "integrator/indirect_light.h"
#include "scene/obj_writer.h"
#include "settings/setting_table.h"

namespace lueur {

void check_export_path(const std::string& obj_path) {
  namespace fs = std::filesystem;
  std::string extension = fs::path(obj_path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".obj") throw IoError("cannot write '" + obj_path + "': an export is an OBJ file (name it FILE.obj)");
  check_writable_path(obj_path);
}

void export_scene(const AppOptions& options) {
  check_export_path(options.export_scene);
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
