// The window's state and the steps of its main loop (Viewer::run, viewer.cpp). One class, because the steps share
// the panel's model and the tracers; its member functions are defined by job, one file each:
//   viewer.cpp              the main loop, a short list of steps
//   viewer_window.cpp       the GLFW window, its callbacks and ImGui's back-ends around the loop (run_viewer)
//   viewer_scene.cpp        loading, reloading and watching the scene
//   viewer_input.cpp        mouse, keys and the camera they move; the panel's Tab and the window's layout
//   viewer_actions.cpp      the panel's buttons: saving images and views, opening scenes, camera shortcuts
//   viewer_tracers.cpp      the tracer and the A/B split's second one: settings in, snapshots out
//   viewer_noise.cpp        the noise estimate of each side and the pause at a target noise
//   viewer_draw.cpp         the image (or the split) through the display pipelines, and the pixel inspector
//   viewer_state_file.cpp   frame pacing, frame statistics and the JSON state file the window test reads
// Part of src/app: it sees GLFW and ImGui, which the core library never does.
#pragma once

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/options.h"
#include "app/scene_loading.h"
#include "core/file_watch.h"
#include "display/display_pipeline.h"
#include "display/window_layout.h"
#include "film/noise_estimate.h"
#include "runtime/progressive_tracer.h"
#include "ui/camera_drag.h"
#include "ui/mouse_buttons.h"
#include "ui/panel.h"

namespace lueur {

using ViewerClock = std::chrono::steady_clock;

inline double seconds_between(ViewerClock::time_point a, ViewerClock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// Input the GLFW callbacks collect between frames.
struct InputEvents {
  double scroll = 0.0;
  std::vector<std::string> dropped;
  int tab_presses = 0;   ///< counted by the key callback: a quick tap can fall between two polls of the key's state
  MouseButtons buttons;  ///< what ImGui and the camera see, one change per button per frame
  double cursor_x = 0.0, cursor_y = 0.0;  ///< the cursor as the position events left it, in their order
};

InputEvents& events_of(GLFWwindow* window);

class Viewer {
 public:
  Viewer(const AppOptions& options, GLFWwindow* window, const GlApi& gl);
  void run();

 private:
  // ---- the loop's steps (viewer.cpp) ------------------------------------------------------------------------
  void begin_frame();
  PanelActions lay_out_and_draw_panel();
  void end_frame(ViewerClock::time_point frame_start);

  // ---- scenes (viewer_scene.cpp) ----------------------------------------------------------------------------
  void start_loading(const std::string& path, bool initial, bool keep_camera = false);
  void finish_loading();
  void reload_scene();
  void reload_if_files_changed();
  void reload_if_needed();
  void watch_after_failure(const std::string& failed_path);

  // ---- input (viewer_input.cpp) -----------------------------------------------------------------------------
  void deliver_mouse_buttons();
  bool drag_divider(const InputEvents& events);
  void handle_input();
  void drag_camera(InputEvents& events, CameraSpec& camera);
  void handle_keys(CameraSpec& camera);
  float aspect() const;
  WindowLayout current_layout() const;
  void toggle_panel();

  // ---- panel buttons (viewer_actions.cpp) -------------------------------------------------------------------
  void handle_actions(const PanelActions& actions);
  Settings settings_with_shown_frames() const;
  void load_view(const std::string& path);
  void save_image(const char* extension);
  void set_message(const std::string& text, bool error);

  // ---- tracers (viewer_tracers.cpp) -------------------------------------------------------------------------
  void apply_to_tracer();
  void apply_to_right_tracer();
  void take_snapshots();

  // ---- noise (viewer_noise.cpp) -----------------------------------------------------------------------------
  void update_noise();
  void update_right_figures();

  // ---- drawing and the pixel inspector (viewer_draw.cpp) ----------------------------------------------------
  void draw();
  bool split_shown() const;
  void update_probe();

  // ---- pacing, statistics, the state file (viewer_state_file.cpp) -------------------------------------------
  void record_frame_time(ViewerClock::time_point frame_start);
  void pace(ViewerClock::time_point frame_start) const;
  void write_state_file() const;

  const AppOptions& options_;
  GLFWwindow* window_;
  const GlApi& gl_;
  PanelModel panel_;
  WindowLayout layout_;  ///< this frame's: the panel's column and the image beside it
  bool panel_shown_ = true;

  // The scene.
  OpenedScene scene_;
  std::string scene_path_;
  CameraSpec home_camera_;
  std::unique_ptr<SceneLoading> loading_;
  Settings scene_settings_;  ///< the settings the scene (or the one loading) was prepared with
  bool loading_is_initial_ = false, reloading_same_scene_ = false;
  FileWatch scene_watch_;     ///< the files the scene shown was read from
  uint64_t scene_loads_ = 0;  ///< loads started, for the state file

  // Input.
  CameraDrag camera_drag_;
  bool dragging_divider_ = false;
  double last_key_time_ = 0.0;
  bool f5_was_down_ = false, f_was_down_ = false, r_was_down_ = false, i_was_down_ = false, o_was_down_ = false;

  // The tracers and what they last published.
  DisplayPipeline pipeline_;
  DisplayPipeline right_pipeline_;     ///< an A/B split's right side
  std::shared_ptr<FrameTurns> turns_;  ///< the two sides take turns, a frame each
  ProgressiveTracer tracer_;
  ProgressiveTracer right_tracer_;  ///< idle (no scene) unless the settings compare something
  std::optional<Settings> right_;   ///< the settings of an A/B split's right side; none without --compare
  TracerSnapshot shown_, shown_right_;

  // The noise estimates.
  RunningNoiseEstimate noise_estimate_, right_noise_estimate_;  ///< each side's, remade at powers of two
  uint64_t noise_generation_ = ~uint64_t{0};                    ///< the accumulation the noise history belongs to
  uint64_t right_noise_generation_ = ~uint64_t{0};
  bool noise_target_met_ = false;  ///< the target stopped this accumulation once: resuming goes on
  bool repeat_reported_ = false;   ///< this accumulation's stop at the end of its sample sequences was said

  // The pixel inspector.
  std::optional<std::pair<double, double>> probe_point_;  ///< the inspected point, as shares of the image's size
  bool right_button_was_down_ = false;

  // Pacing and figures for the state file: display frame intervals and the time from a change to its first frame on
  // screen.
  uint64_t display_frames_ = 0;
  double frame_seconds_ = 0.0;
  std::vector<double> frame_intervals_ms_, restart_latencies_ms_;
  ViewerClock::time_point previous_frame_start_{}, restart_time_{}, last_state_write_{};
  uint64_t awaited_generation_ = 0;
  bool restart_pending_ = false, restart_shown_ = false;
};

}  // namespace lueur
