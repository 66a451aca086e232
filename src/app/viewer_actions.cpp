// The panel's buttons: reset, save an image or a view, load a view, open or reload a scene, and the camera's
// shortcuts; and the panel's one-line message.
#include <ctime>
#include <exception>

#include "app/displayed_image.h"
#include "app/viewer_state.h"
#include "image/image_output.h"
#include "settings/view_file.h"
#include "ui/camera_controls.h"

namespace lueur {
namespace {

std::string timestamped_name(const char* extension) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "lueur-%Y%m%d-%H%M%S", &local);
  return std::string(name) + extension;
}

}  // namespace

void Viewer::handle_actions(const PanelActions& a) {
  if (a.reset) tracer_.reset();
  if (a.save_png) save_image(".png");
  if (a.save_pfm) save_image(".pfm");
  if (a.save_exr) save_image(".exr");
  if (a.save_view) {
    try {
      save_view_file(panel_.view_path, settings_with_shown_frames());
      set_message("saved view " + panel_.view_path, false);
    } catch (const std::exception& e) {
      set_message(e.what(), true);
    }
  }
  if (a.load_view) load_view(panel_.view_path);
  if (a.open_scene) start_loading(panel_.scene_path, false);
  if (a.reload_scene) reload_scene();
  if (scene_.traced && a.frame_scene && panel_.settings.camera)
    panel_.settings.camera = frame_bounds(*panel_.settings.camera, scene_.traced->scene.bounds(), aspect());
  if (scene_.traced && a.reset_camera) panel_.settings.camera = home_camera_;
  if (a.inside_view && scene_.inside_view) panel_.settings.camera = *scene_.inside_view;
  if (a.outside_view && scene_.traced) panel_.settings.camera = scene_.outside_view;
}

/// The settings with the frames shown so far: what a saved view or image renders again.
Settings Viewer::settings_with_shown_frames() const {
  Settings settings = panel_.settings;
  if (shown_.film.frames > 0) settings.frames = static_cast<int>(std::min<uint64_t>(shown_.film.frames, 1000000));
  return settings;
}

void Viewer::load_view(const std::string& path) {
  try {
    Settings loaded = load_view_file(path, panel_.settings);
    loaded.camera = camera_of(loaded, home_camera_);
    loaded.up.reset();
    panel_.settings = loaded;
    // The window grows or shrinks so that the image beside the panel has the view's size.
    glfwSetWindowSize(window_, window_width_for_image(loaded.render.width, panel_shown_ ? panel_.panel_width : 0.0),
                      loaded.render.height);
    set_message("loaded view " + path, false);
  } catch (const std::exception& e) {
    set_message(e.what(), true);
  }
}

void Viewer::save_image(const char* extension) {
  const Film& film = shown_.film;
  if (shown_.preview_divisor != 1 || film.frames == 0) {
    set_message("nothing to save yet: wait for the first full frame", true);
    return;
  }
  const std::string path = timestamped_name(extension);
  try {
    const Settings& s = panel_.settings;
    write_image(path, displayed_image(film, s), film_layer_images(film), displayed_transform(s),
                describe_options(scene_path_, settings_with_shown_frames()));
    set_message("saved " + path, false);
  } catch (const std::exception& e) {
    set_message(e.what(), true);
  }
}

void Viewer::set_message(const std::string& text, bool error) {
  panel_.message = text;
  panel_.message_is_error = error;
}

}  // namespace lueur
