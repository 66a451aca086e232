// The window's main loop: input, panel, apply changes to the tracer, take its newest snapshot, draw.
// The display never waits for the tracer: it only ever swaps in a finished snapshot.
#include "app/viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "accel/embree_backend.h"
#include "app/displayed_image.h"
#include "app/scene_loading.h"
#include "core/atomic_file.h"
#include "core/file_watch.h"
#include "display/display_pipeline.h"
#include "display/split_view.h"
#include "display/window_layout.h"
#include "image/image_output.h"
#include "film/noise_estimate.h"
#include "film/pixel_probe.h"
#include "runtime/progressive_tracer.h"
#include "settings/compare.h"
#include "settings/setting_table.h"
#include "settings/view_file.h"
#include "ui/camera_controls.h"
#include "ui/imgui_gl.h"
#include "ui/mouse_buttons.h"
#include "ui/panel.h"
#include "ui/pixel_inspector.h"

namespace lueur {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// Input the GLFW callbacks collect between frames.
struct InputEvents {
  double scroll = 0.0;
  std::vector<std::string> dropped;
  int tab_presses = 0;   ///< counted by the key callback: a quick tap can fall between two polls of the key's state
  MouseButtons buttons;  ///< what ImGui and the camera see, one change per button per frame
};

InputEvents& events_of(GLFWwindow* window) { return *static_cast<InputEvents*>(glfwGetWindowUserPointer(window)); }

std::string timestamped_name(const char* extension) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "lueur-%Y%m%d-%H%M%S", &local);
  return std::string(name) + extension;
}

bool has_extension(const std::string& path, const std::string& extension) {
  if (path.size() < extension.size()) return false;
  std::string tail = path.substr(path.size() - extension.size());
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == extension;
}

class Viewer {
 public:
  Viewer(const AppOptions& options, GLFWwindow* window, const GlApi& gl)
      : options_(options),
        window_(window),
        gl_(gl),
        pipeline_(gl),
        right_pipeline_(gl),
        turns_(std::make_shared<FrameTurns>()),
        tracer_(options.threads, turns_),
        right_tracer_(options.threads, turns_) {
    panel_.settings = options.settings;
    panel_.scene_path = options.scene_path;
    panel_.paused = false;
    tracer_.set_frame_limit(panel_.settings.frame_limit);
    start_loading(options.scene_path, true);
  }

  void run() {
    Clock::time_point last_state_write{};
    while (!glfwWindowShouldClose(window_)) {
      const Clock::time_point frame_start = Clock::now();
      if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED))
        glfwWaitEventsTimeout(0.1);  // minimised: nothing to draw, the tracer keeps its size
      else
        glfwPollEvents();
      finish_loading();

      imgui_opengl_new_frame();
      ImGui_ImplGlfw_NewFrame();
      deliver_mouse_buttons();
      ImGui::NewFrame();
      panel_.stats = tracer_.stats();
      panel_.status = loading_ ? loading_->status() : std::string();
      toggle_panel();
      layout_ = current_layout();
      PanelActions actions;
      if (panel_shown_)
        actions = draw_panel(panel_, static_cast<float>(layout_.image.height), layout_.panel_over_image);
      else
        panel_.widget_rects.clear();
      layout_ = current_layout();  // the panel's edge may have been dragged
      handle_input();
      handle_actions(actions);
      reload_if_needed();
      reload_if_files_changed();
      apply_to_tracer();
      draw();
      update_probe();
      ImGui::Render();
      imgui_opengl_render();
      glfwSwapBuffers(window_);
      ++display_frames_;
      record_frame_time(frame_start);
      if (restart_shown_) {
        restart_latencies_ms_.push_back(1e3 * seconds_between(restart_time_, Clock::now()));
        restart_shown_ = false;
      }
      if (!options_.state_file.empty() && seconds_between(last_state_write, Clock::now()) > 0.1) {
        write_state_file();
        last_state_write = Clock::now();
      }
      pace(frame_start);
    }
    if (!options_.state_file.empty()) write_state_file();
  }

 private:
  // ---- scenes -----------------------------------------------------------------------------------------------
  /// Starts loading `path` (empty: the default scene) in the background; `keep_camera` when it is the scene shown,
  /// read again. A load started before it is done is dropped.
  void start_loading(const std::string& path, bool initial, bool keep_camera = false) {
    loading_ = std::make_unique<SceneLoading>(path, scene_options_of(panel_.settings), aspect());
    ++scene_loads_;
    loading_is_initial_ = initial;
    reloading_same_scene_ = keep_camera;
    scene_settings_ = panel_.settings;
  }

  void finish_loading() {
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
  void reload_scene() {
    if (loading_) return;  // the load in progress reads the files as they are now
    start_loading(scene_path_, !scene_.traced, scene_.traced != nullptr);
  }

  /// With the watch setting on, reloads once the scene's files have changed on disk and stopped changing.
  void reload_if_files_changed() {
    if (loading_ || !panel_.settings.watch || !scene_watch_.changed(glfwGetTime())) return;
    set_message(scene_path_ + " changed on disk: reloading", false);
    reload_scene();
  }

  /// A load that failed leaves the scene shown as it was. Where it was that scene's own files (a reload, or the
  /// first scene), they are watched again as they are now, so that the broken files are not reloaded over and over
  /// and the next save (the fix) is.
  void watch_after_failure(const std::string& failed_path) {
    if (scene_.traced && failed_path != scene_path_) return;  // another file failed: the scene shown keeps its watch
    std::vector<WatchedFile> files = scene_.traced ? scene_watch_.files() : std::vector<WatchedFile>{};
    if (files.empty()) files.push_back({failed_path, {}});
    for (WatchedFile& file : files) file.stamp = stamp_file(file.path);
    scene_watch_.watch(std::move(files));
    scene_path_ = failed_path;
  }

  // ---- input ------------------------------------------------------------------------------------------------
  /// Replaces the buttons ImGui's GLFW back-end polled with the queued ones (see ui/mouse_buttons.h).
  void deliver_mouse_buttons() {
    MouseButtons& buttons = events_of(window_).buttons;
    buttons.next_frame();
    ImGuiIO& io = ImGui::GetIO();
    for (int b = 0; b < MouseButtons::kCount; ++b) io.MouseDown[b] = buttons.down[static_cast<size_t>(b)];
  }

  /// An A/B split's divider follows a left drag that starts on it (within a few pixels) outside the panel; true
  /// while it does, so that the drag does not also turn the camera.
  bool drag_divider(const InputEvents& events) {
    const bool left = events.buttons.down[GLFW_MOUSE_BUTTON_LEFT];
    const WindowRect& image = layout_.image;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    if (!left || !right_ || image.width <= 0.0) {
      dragging_divider_ = false;
      return false;
    }
    const double divider = image.x + panel_.settings.compare_split * image.width;
    if (!dragging_divider_ && !dragging_ && !ImGui::GetIO().WantCaptureMouse && std::abs(x - divider) <= 6.0)
      dragging_divider_ = true;
    if (!dragging_divider_) return false;
    panel_.settings.compare_split = static_cast<float>(std::clamp((x - image.x) / image.width, 0.0, 1.0));
    last_cursor_x_ = x;
    last_cursor_y_ = y;
    return true;
  }

  void handle_input() {
    InputEvents& events = events_of(window_);
    for (const std::string& path : events.dropped) {
      if (has_extension(path, ".json"))
        load_view(path);
      else
        start_loading(path, false);
    }
    events.dropped.clear();
    // F5 works with no scene too: after a first scene that failed to load, it tries again.
    const bool f5 = !ImGui::GetIO().WantCaptureKeyboard && glfwGetKey(window_, GLFW_KEY_F5) == GLFW_PRESS;
    if (f5 && !f5_was_down_) reload_scene();
    f5_was_down_ = f5;
    if (drag_divider(events)) return;
    if (!panel_.settings.camera) {
      events.scroll = 0.0;
      return;
    }
    CameraSpec& camera = *panel_.settings.camera;
    const ImGuiIO& io = ImGui::GetIO();
    const double height = layout_.image.height;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    const float dx = static_cast<float>(x - last_cursor_x_), dy = static_cast<float>(y - last_cursor_y_);
    last_cursor_x_ = x;
    last_cursor_y_ = y;

    // A drag belongs to the view only when it started outside the panel.
    const bool left = events.buttons.down[GLFW_MOUSE_BUTTON_LEFT];
    const bool middle = events.buttons.down[GLFW_MOUSE_BUTTON_MIDDLE];
    if (!left && !middle)
      dragging_ = false;
    else if (!dragging_ && !io.WantCaptureMouse)
      dragging_ = true;
    if (dragging_ && height > 0 && (dx != 0.0f || dy != 0.0f)) {
      const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                         glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
      const float h = static_cast<float>(height);
      if (middle || shift)
        camera = pan(camera, dx / h, dy / h);
      else
        camera = orbit(camera, 3.0f * dx / h, -3.0f * dy / h);
    }
    if (events.scroll != 0.0 && !io.WantCaptureMouse) camera = dolly(camera, static_cast<float>(events.scroll));
    events.scroll = 0.0;

    if (io.WantCaptureKeyboard) return;
    const double now = glfwGetTime();
    const float dt = static_cast<float>(std::min(0.1, now - last_key_time_));
    last_key_time_ = now;
    const float speed = 0.4f * (scene_.traced ? scene_.traced->diagonal : 1.0f) * dt;
    const auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
    const float forward = down(GLFW_KEY_W) - down(GLFW_KEY_S), right = down(GLFW_KEY_D) - down(GLFW_KEY_A),
                up = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
    if (forward != 0.0f || right != 0.0f || up != 0.0f)
      camera = fly(camera, forward * speed, right * speed, up * speed);
    const bool f = down(GLFW_KEY_F) > 0.0f, r = down(GLFW_KEY_R) > 0.0f;
    const bool i = down(GLFW_KEY_I) > 0.0f, o = down(GLFW_KEY_O) > 0.0f;
    if (f && !f_was_down_ && scene_.traced) camera = frame_bounds(camera, scene_.traced->scene.bounds(), aspect());
    if (r && !r_was_down_ && scene_.traced) camera = home_camera_;
    if (i && !i_was_down_ && scene_.inside_view) camera = *scene_.inside_view;
    if (o && !o_was_down_ && scene_.traced) camera = scene_.outside_view;
    f_was_down_ = f;
    r_was_down_ = r;
    i_was_down_ = i;
    o_was_down_ = o;
  }

  /// The image's aspect ratio, as laid out beside the panel.
  float aspect() const {
    const PixelRect& image = current_layout().image_pixels;
    return image.width > 0 && image.height > 0 ? static_cast<float>(image.width) / static_cast<float>(image.height)
                                               : 1.0f;
  }

  /// The window shared between the panel (when shown) and the image, as it stands now.
  WindowLayout current_layout() const {
    int window_width = 0, window_height = 0, fb_width = 0, fb_height = 0;
    glfwGetWindowSize(window_, &window_width, &window_height);
    glfwGetFramebufferSize(window_, &fb_width, &fb_height);
    return lay_out_window(window_width, window_height, fb_width, fb_height, panel_shown_ ? panel_.panel_width : 0.0);
  }

  /// Tab hides the panel (the image takes the whole window) and shows it again; not while a text field has the keys.
  void toggle_panel() {
    int& presses = events_of(window_).tab_presses;
    if (!ImGui::GetIO().WantCaptureKeyboard && presses % 2 == 1) panel_shown_ = !panel_shown_;
    presses = 0;
  }

  // ---- panel buttons ----------------------------------------------------------------------------------------
  void handle_actions(const PanelActions& a) {
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

  /// A change to a setting that shapes the traced scene (smooth normals, the accelerator: the table's kReload)
  /// prepares the same scene again; the old one is traced until the new one is ready.
  void reload_if_needed() {
    if (loading_ || !scene_.traced) return;  // checked again once the load in progress is done
    if (change_effect(scene_settings_, panel_.settings) != SettingEffect::kReload) return;
    if (panel_.settings.accel == AccelKind::kEmbree && !embree_available()) {
      panel_.settings.accel = scene_settings_.accel;
      set_message("this build has no Embree (install libembree-dev and rebuild)", true);
      if (change_effect(scene_settings_, panel_.settings) != SettingEffect::kReload) return;
    }
    start_loading(scene_path_, false, true);
  }

  /// The settings with the frames shown so far: what a saved view or image renders again.
  Settings settings_with_shown_frames() const {
    Settings settings = panel_.settings;
    if (shown_.film.frames > 0) settings.frames = static_cast<int>(std::min<uint64_t>(shown_.film.frames, 1000000));
    return settings;
  }

  void load_view(const std::string& path) {
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

  void save_image(const char* extension) {
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

  void set_message(const std::string& text, bool error) {
    panel_.message = text;
    panel_.message_is_error = error;
  }

  // ---- tracer and display -----------------------------------------------------------------------------------
  void apply_to_tracer() {
    const int w = layout_.image_pixels.width, h = layout_.image_pixels.height;
    if (w > 0 && h > 0) {  // a minimised window (0 x 0) keeps the last size
      panel_.settings.render.width = w;
      panel_.settings.render.height = h;
    }
    const uint64_t generation = tracer_.generation();
    tracer_.set_settings(panel_.settings.render);
    if (panel_.settings.camera) tracer_.set_camera(*panel_.settings.camera);
    if (tracer_.generation() != generation) {
      // Latency is measured from the first change not yet on screen, as a user dragging would feel it.
      if (!restart_pending_) restart_time_ = Clock::now();
      restart_pending_ = true;
      awaited_generation_ = tracer_.generation();
    }
    tracer_.set_paused(panel_.paused);
    tracer_.set_frame_limit(panel_.settings.frame_limit);
    tracer_.set_time_limit(panel_.settings.time_limit);
    apply_to_right_tracer();
  }

  /// The A/B split's right side: the same scene and camera, the settings with the compared one changed. Changing
  /// only the compared value restarts only this side.
  void apply_to_right_tracer() {
    try {
      right_ = compared_settings(panel_.settings);
    } catch (const std::exception& e) {
      set_message(std::string("--compare: ") + e.what(), true);
      panel_.settings.compare.clear();
      right_.reset();
    }
    panel_.comparing = right_.has_value();
    right_tracer_.set_scene(right_ ? scene_.traced : nullptr);
    if (!right_) return;
    right_tracer_.set_settings(right_->render);
    if (panel_.settings.camera) right_tracer_.set_camera(*panel_.settings.camera);
    right_tracer_.set_paused(panel_.paused);
    right_tracer_.set_frame_limit(panel_.settings.frame_limit);
    right_tracer_.set_time_limit(panel_.settings.time_limit);
  }

  /// The right side's estimated error and tracing time, for the panel.
  void update_right_figures() {
    if (shown_right_.generation != right_noise_generation_) {
      right_noise_generation_ = shown_right_.generation;
      right_noise_estimate_.reset();
      panel_.right_noise = NoiseEstimate{};
    }
    if (!right_ || shown_right_.preview_divisor != 1) return;
    panel_.right_noise =
        right_noise_estimate_.update(shown_right_.film, right_->render.enabled, right_->weights, right_->render.sampler)
            .image;
    panel_.right_stats = shown_right_.stats;
  }

  /// The shown film's noise estimate, its history since the accumulation began, and the stop at a target noise.
  void update_noise() {
    if (shown_.generation != noise_generation_) {
      noise_generation_ = shown_.generation;
      panel_.noise_history.clear();
      panel_.noise = FilmNoise{};
      noise_estimate_.reset();
      noise_target_met_ = false;
    }
    if (shown_.preview_divisor != 1) return;
    const Settings& s = panel_.settings;
    panel_.noise = noise_estimate_.update(shown_.film, s.render.enabled, s.weights, s.render.sampler);
    record_noise(panel_, panel_.noise, shown_.stats.seconds);
    const NoiseEstimate& image = panel_.noise.image;
    if (s.target_noise > 0.0f && image.known && image.rel_mse < s.target_noise && !noise_target_met_) {
      noise_target_met_ = true;
      panel_.paused = true;
      char text[160];
      std::snprintf(text, sizeof text, "target noise %g reached after %llu frames, %.1f s: paused",
                    static_cast<double>(s.target_noise), static_cast<unsigned long long>(shown_.film.frames),
                    shown_.stats.seconds);
      set_message(text, false);
    }
  }

  void draw() {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (tracer_.take_snapshot(shown_)) {
      if (restart_pending_ && shown_.generation >= awaited_generation_) {
        restart_pending_ = false;
        restart_shown_ = true;
      }
      panel_.film_width = shown_.film.width;
      panel_.film_height = shown_.film.height;
      panel_.preview_divisor = shown_.preview_divisor;
      update_noise();
    }
    if (right_tracer_.take_snapshot(shown_right_)) update_right_figures();
    if (w <= 0 || h <= 0) return;
    const Settings& shown = panel_.settings;
    if (shown_.film.width > 0) pipeline_.update(shown_.film, shown_.version, shown);
    const bool split = split_shown();
    if (split) right_pipeline_.update(shown_right_.film, shown_right_.version, *right_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl_.ClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
    const PixelRect full{0, 0, w, h};
    const PixelRect& image = layout_.image_pixels;
    if (image.width <= 0 || image.height <= 0) return;
    if (split)
      draw_split_view(gl_, pipeline_, shown, right_pipeline_, *right_, full, image);
    else if (shown_.film.width > 0)
      pipeline_.draw(shown, full, image);
    if (shown.layer && shown_.film.width > 0 && !shown_.film.has(*shown.layer))
      set_message("view " + std::string(kLayerNames[static_cast<size_t>(*shown.layer)]) +
                      " is not rendered with these passes and reuse settings",
                  true);
  }

  /// Whether the A/B split shows: once the right side has a frame of the same size as the left's.
  bool split_shown() const {
    return right_ && shown_.film.width > 0 && shown_right_.film.width == shown_.film.width &&
           shown_right_.film.height == shown_.film.height;
  }

  /// The pixel inspector's pixel: the one under the mouse while it is over the image (the last one while it is over
  /// the panel), or the one a right click pinned, outlined. Read from the film shown on that side of an A/B split.
  void update_probe() {
    const WindowRect& image = layout_.image;
    const double width = image.width, height = image.height;
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window_, &x, &y);
    const bool over_image = !ImGui::GetIO().WantCaptureMouse && image.contains(x, y);
    x -= image.x;
    const bool right_button = events_of(window_).buttons.down[GLFW_MOUSE_BUTTON_RIGHT];
    if (right_button && !right_button_was_down_ && over_image) {
      panel_.probe_pinned = !panel_.probe_pinned;
      panel_.probe_history.clear();
      if (panel_.probe_pinned) probe_point_ = {x / width, y / height};
    }
    right_button_was_down_ = right_button;
    if (!panel_.probe_pinned && over_image) probe_point_ = {x / width, y / height};
    panel_.probe.reset();
    if (!probe_point_ || width <= 0.0 || height <= 0.0) return;
    // The point is kept as a share of the image, so that a pinned pixel stays put through previews and resizes.
    const double px = probe_point_->first * width, py = probe_point_->second * height;
    const bool right_side = split_shown() && px >= panel_.settings.compare_split * width;
    const TracerSnapshot& shown = right_side ? shown_right_ : shown_;
    const Settings& settings = right_side ? *right_ : panel_.settings;
    const std::optional<FilmPixel> pixel = film_pixel_at(px, py, width, height, shown.film.width, shown.film.height);
    if (!pixel) return;
    panel_.probe = probe_pixel(shown.film, *pixel, settings.render.enabled, settings.weights);
    panel_.probe_right_side = right_side;
    record_probe(panel_);
    if (panel_.probe_pinned) {
      const float sx = static_cast<float>(width) / static_cast<float>(shown.film.width);
      const float sy = static_cast<float>(height) / static_cast<float>(shown.film.height);
      const float x0 = static_cast<float>(image.x);
      draw_pixel_marker(x0 + static_cast<float>(pixel->x) * sx, static_cast<float>(pixel->y) * sy,
                        x0 + static_cast<float>(pixel->x + 1) * sx, static_cast<float>(pixel->y + 1) * sy);
    }
  }

  void record_frame_time(Clock::time_point frame_start) {
    if (previous_frame_start_ != Clock::time_point{}) {
      // The interval between frames, as the user sees it (pacing included), over the last 600 frames.
      if (frame_intervals_ms_.size() == 600) frame_intervals_ms_.erase(frame_intervals_ms_.begin());
      frame_intervals_ms_.push_back(1e3 * seconds_between(previous_frame_start_, frame_start));
    }
    previous_frame_start_ = frame_start;
    const double seconds = seconds_between(frame_start, Clock::now());
    frame_seconds_ = frame_seconds_ == 0.0 ? seconds : 0.9 * frame_seconds_ + 0.1 * seconds;
    panel_.display_fps = frame_seconds_ > 0.0 ? 1.0 / frame_seconds_ : 0.0;
  }

  /// Without a working vsync (Xvfb, some drivers) the loop would spin; cap it at the monitor's refresh rate.
  void pace(Clock::time_point frame_start) const {
    const GLFWvidmode* mode = glfwGetVideoMode(glfwGetPrimaryMonitor());
    const double refresh = mode && mode->refreshRate > 0 ? mode->refreshRate : 60.0;
    const double left = 1.0 / refresh - seconds_between(frame_start, Clock::now());
    if (left > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
  }

  void write_state_file() const {
    nlohmann::json state;
    state["view"] = nlohmann::json::parse(view_to_json(panel_.settings));
    const TracerStats stats = tracer_.stats();
    state["frames"] = stats.frames;
    state["generation"] = tracer_.generation();
    state["right_frames"] = right_tracer_.stats().frames;  // an A/B split's right side
    state["right_generation"] = right_tracer_.generation();
    state["shown_frames"] = shown_.film.frames;
    state["shown_generation"] = shown_.generation;
    state["display_frames"] = display_frames_;
    state["display_fps"] = panel_.display_fps;
    if (!frame_intervals_ms_.empty()) {
      std::vector<double> sorted = frame_intervals_ms_;
      std::sort(sorted.begin(), sorted.end());
      state["frame_interval_ms"] = {{"median", sorted[sorted.size() / 2]}, {"worst", sorted.back()}};
    }
    state["restart_latency_ms"] = restart_latencies_ms_;
    state["last_frame_seconds"] = stats.last_frame_seconds;
    state["paused"] = panel_.paused;
    state["scene"] = panel_.scene_name;
    state["triangles"] = panel_.triangles;
    state["automatic_ao_radius"] = panel_.automatic_ao_radius;
    state["loading"] = loading_ != nullptr;
    state["scene_loads"] = scene_loads_;
    if (panel_.probe) {
      const PixelProbe& probe = *panel_.probe;
      nlohmann::json layers;
      for (size_t l = 0; l < static_cast<size_t>(kLayerCount); ++l)
        if (probe.layers[l]) layers[std::string(kLayerNames[l])] = {probe.layers[l]->r, probe.layers[l]->g, probe.layers[l]->b};
      state["probe"] = {{"x", probe.pixel.x},
                        {"y", probe.pixel.y},
                        {"frames", probe.frames},
                        {"pinned", panel_.probe_pinned},
                        {"right_side", panel_.probe_right_side},
                        {"image", {probe.combined.r, probe.combined.g, probe.combined.b}},
                        {"layers", layers},
                        {"history", panel_.probe_history.size()}};
    }
    state["message"] = panel_.message;
    state["message_is_error"] = panel_.message_is_error;
    nlohmann::json widgets;
    for (const auto& [name, rect] : panel_.widget_rects) widgets[name] = rect;
    state["widgets"] = widgets;
    try {
      write_file_atomically(options_.state_file, state.dump(2));
    } catch (const IoError&) {
      // A test harness reading the file must never take the window down.
    }
  }

  const AppOptions& options_;
  GLFWwindow* window_;
  const GlApi& gl_;
  DisplayPipeline pipeline_;
  DisplayPipeline right_pipeline_;     ///< an A/B split's right side
  std::shared_ptr<FrameTurns> turns_;  ///< the two sides take turns, a frame each
  ProgressiveTracer tracer_;
  ProgressiveTracer right_tracer_;  ///< idle (no scene) unless the settings compare something
  PanelModel panel_;
  OpenedScene scene_;
  std::string scene_path_;
  CameraSpec home_camera_;
  std::unique_ptr<SceneLoading> loading_;
  Settings scene_settings_;  ///< the settings the scene (or the one loading) was prepared with
  bool loading_is_initial_ = false, reloading_same_scene_ = false;
  TracerSnapshot shown_, shown_right_;
  RunningNoiseEstimate noise_estimate_, right_noise_estimate_;  ///< each side's, remade at powers of two
  uint64_t right_noise_generation_ = ~uint64_t{0};
  std::optional<Settings> right_;  ///< the settings of an A/B split's right side; none without --compare
  bool dragging_divider_ = false;
  bool panel_shown_ = true;
  WindowLayout layout_;  ///< this frame's: the panel's column and the image beside it
  uint64_t display_frames_ = 0;
  double frame_seconds_ = 0.0;
  double last_cursor_x_ = 0.0, last_cursor_y_ = 0.0, last_key_time_ = 0.0;
  FileWatch scene_watch_;  ///< the files the scene shown was read from
  uint64_t scene_loads_ = 0;  ///< loads started, for the state file
  bool f5_was_down_ = false;
  std::optional<std::pair<double, double>> probe_point_;  ///< the inspected point, as shares of the window's size
  bool right_button_was_down_ = false;
  bool dragging_ = false, f_was_down_ = false, r_was_down_ = false, i_was_down_ = false, o_was_down_ = false;
  // Figures for the state file: display frame intervals and the time from a change to its first frame on screen.
  std::vector<double> frame_intervals_ms_, restart_latencies_ms_;
  Clock::time_point previous_frame_start_{}, restart_time_{};
  uint64_t awaited_generation_ = 0;
  uint64_t noise_generation_ = ~uint64_t{0};  ///< the accumulation the noise history belongs to
  bool noise_target_met_ = false;             ///< the target stopped this accumulation once: resuming goes on
  bool restart_pending_ = false, restart_shown_ = false;
};

GlProc glfw_get_proc(const char* name) { return reinterpret_cast<GlProc>(glfwGetProcAddress(name)); }

}  // namespace

int run_viewer(const AppOptions& options) {
  if (!glfwInit())
    throw std::runtime_error("cannot open a window (no display?): render to a file with --headless --out FILE");
  struct GlfwTerminate {
    ~GlfwTerminate() { glfwTerminate(); }
  } terminate;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // Wide enough for the image at its size beside the panel.
  GLFWwindow* window = glfwCreateWindow(window_width_for_image(options.settings.render.width, kPanelWidth),
                                        options.settings.render.height, "Lueur", nullptr, nullptr);
  if (!window) throw std::runtime_error("cannot create an OpenGL 3.3 core window");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  InputEvents events;
  glfwSetWindowUserPointer(window, &events);
  // Installed before ImGui's, which chains to them.
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) { events_of(w).scroll += y; });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    events_of(w).buttons.record(button, action == GLFW_PRESS);
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (key == GLFW_KEY_TAB && action == GLFW_PRESS) ++events_of(w).tab_presses;
  });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    for (int i = 0; i < count; ++i) events_of(w).dropped.emplace_back(paths[i]);
  });

  const GlApi gl = load_gl_api(glfw_get_proc);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the panel's layout is Lueur's, not a file in the working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  init_imgui_opengl(glfw_get_proc);
  {
    Viewer viewer(options, window, gl);
    viewer.run();
  }
  shutdown_imgui_opengl();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  return 0;
}

}  // namespace lueur
