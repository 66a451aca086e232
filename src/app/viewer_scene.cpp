// The scene shown in the window: loaded in the background (the old scene stays until the new one is ready, and an
// error leaves it there), read again on F5, on a setting that reshapes it, or when its files change on disk.
#include "accel/embree_backend.h"
#include "app/viewer_state.h"
#include "settings/setting_table.h"

namespace lueur {

/// Starts loading `path` (empty: the default scene) in the background; `keep_camera` when it is the scene shown,
/// read again. A load started before it is done is dropped.
void Viewer::start_loading(const std::string& path, bool initial, bool keep_camera) {
  loading_ = std::make_unique<SceneLoading>(path, scene_options_of(panel_.settings), aspect());
  ++scene_loads_;
  loading_is_initial_ = initial;
  reloading_same_scene_ = keep_camera;
  scene_settings_ = panel_.settings;
}

void Viewer::finish_loading() {
  if (!loading_ || !loading_->finished()) return;
  std::optional<OpenedScene> opened = loading_->take_result();
  if (!opened) {
    // The old scene stays; the error goes to the panel.
    set_message("cannot load: " + loading_->error(), true);
    watch_after_failure(loading_->path());
    loading_.reset();
    reloading_same_scene_ = false;
    return;
  }
  const bool keep_camera = reloading_same_scene_;
  scene_path_ = loading_->path();
  panel_.scene_path = scene_path_;
  loading_.reset();
  reloading_same_scene_ = false;
  scene_watch_.watch(opened->files);
  scene_ = std::move(*opened);
  // The first scene starts from the camera the options gave, if any; a new scene from its own default view.
  home_camera_ = loading_is_initial_ ? camera_of(options_.settings, scene_.default_view) : scene_.default_view;
  if (!keep_camera) panel_.settings.camera = home_camera_;
  panel_.settings.up.reset();  // the window moves one camera, its up vector included
  describe_scene(panel_, *scene_.traced);
  panel_.closed_room = scene_.inside_view.has_value();
  std::string message;
  for (const std::string& w : scene_.warnings) message += (message.empty() ? "warning: " : "; ") + w;
  for (const std::string& note : scene_.notes) message += (message.empty() ? "" : "; ") + note;
  if (!message.empty())
    set_message(message, false);
  else if (keep_camera)
    set_message("reloaded " + scene_path_, false);
  tracer_.set_scene(scene_.traced);
}

/// Loads the scene shown again from its files, keeping the camera (F5, the panel's Reload, or a change on disk).
/// Before any scene loaded (the first one failed), it tries that one again as a first load.
void Viewer::reload_scene() {
  if (loading_) return;  // the load in progress reads the files as they are now
  start_loading(scene_path_, !scene_.traced, scene_.traced != nullptr);
}

/// With the watch setting on, reloads once the scene's files have changed on disk and stopped changing.
void Viewer::reload_if_files_changed() {
  if (loading_ || !panel_.settings.watch || !scene_watch_.changed(glfwGetTime())) return;
  set_message(scene_path_ + " changed on disk: reloading", false);
  reload_scene();
}

/// A change to a setting that shapes the traced scene (smooth normals, the accelerator: the table's kReload)
/// prepares the same scene again; the old one is traced until the new one is ready.
void Viewer::reload_if_needed() {
  if (loading_ || !scene_.traced) return;  // checked again once the load in progress is done
  if (change_effect(scene_settings_, panel_.settings) != SettingEffect::kReload) return;
  if (panel_.settings.accel == AccelKind::kEmbree && !embree_available()) {
    panel_.settings.accel = scene_settings_.accel;
    set_message("this build has no Embree (install libembree-dev and rebuild)", true);
    if (change_effect(scene_settings_, panel_.settings) != SettingEffect::kReload) return;
  }
  start_loading(scene_path_, false, true);
}

/// A load that failed leaves the scene shown as it was. Where it was that scene's own files (a reload, or the
/// first scene), they are watched again as they are now, so that the broken files are not reloaded over and over
/// and the next save (the fix) is.
void Viewer::watch_after_failure(const std::string& failed_path) {
  if (scene_.traced && failed_path != scene_path_) return;  // another file failed: the scene shown keeps its watch
  std::vector<WatchedFile> files = scene_.traced ? scene_watch_.files() : std::vector<WatchedFile>{};
  if (files.empty()) files.push_back({failed_path, {}});
  for (WatchedFile& file : files) file.stamp = stamp_file(file.path);
  scene_watch_.watch(std::move(files));
  scene_path_ = failed_path;
}

}  // namespace lueur
