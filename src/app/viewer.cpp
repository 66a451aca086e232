// The window's main loop: input, panel, apply changes to the tracer, take its newest snapshot, draw. The display
// never waits for the tracer: it only ever swaps in a finished snapshot. Each step is defined in the file of its job
// (app/viewer_state.h lists them).
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include "app/viewer_state.h"
#include "ui/imgui_gl.h"

namespace lueur {

Viewer::Viewer(const AppOptions& options, GLFWwindow* window, const GlApi& gl)
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

void Viewer::run() {
  while (!glfwWindowShouldClose(window_)) {
    const ViewerClock::time_point frame_start = ViewerClock::now();
    begin_frame();
    finish_loading();
    const PanelActions actions = lay_out_and_draw_panel();
    handle_input();
    handle_actions(actions);
    reload_if_needed();
    reload_if_files_changed();
    apply_to_tracer();
    take_snapshots();
    draw();
    update_probe();
    end_frame(frame_start);
    pace(frame_start);
  }
  if (!options_.state_file.empty()) write_state_file();
}

/// Events in, and a new UI frame begun.
void Viewer::begin_frame() {
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED))
    glfwWaitEventsTimeout(0.1);  // minimised: nothing to draw, the tracer keeps its size
  else
    glfwPollEvents();
  imgui_opengl_new_frame();
  ImGui_ImplGlfw_NewFrame();
  deliver_mouse_buttons();
  ImGui::NewFrame();
}

/// The panel beside the image (unless Tab hid it), with the tracer's figures; returns the buttons it reports.
PanelActions Viewer::lay_out_and_draw_panel() {
  panel_.stats = tracer_.stats();
  panel_.status = loading_ ? loading_->status() : std::string();
  panel_.status_done = loading_ ? loading_->stage_done() : -1.0;
  panel_.status_stages = loading_ ? loading_->finished_stages() : std::vector<std::string>();
  toggle_panel();
  layout_ = current_layout();
  PanelActions actions;
  if (panel_shown_)
    actions = draw_panel(panel_, static_cast<float>(layout_.image.height), layout_.panel_over_image);
  else
    panel_.widget_rects.clear();
  layout_ = current_layout();  // the panel's edge may have been dragged
  return actions;
}

/// The UI drawn over the image, the frame shown, and its figures kept.
void Viewer::end_frame(ViewerClock::time_point frame_start) {
  ImGui::Render();
  imgui_opengl_render();
  glfwSwapBuffers(window_);
  ++display_frames_;
  record_frame_time(frame_start);
  if (restart_shown_) {
    restart_latencies_ms_.push_back(1e3 * seconds_between(restart_time_, ViewerClock::now()));
    restart_shown_ = false;
  }
  if (!options_.state_file.empty() && seconds_between(last_state_write_, ViewerClock::now()) > 0.1) {
    write_state_file();
    last_state_write_ = ViewerClock::now();
  }
}

}  // namespace lueur
