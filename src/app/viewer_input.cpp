// The window's mouse and keys: dropped files, F5, the A/B split's divider, the camera's drags (measured from the
// press, ui/camera_drag.h), the wheel and the fly keys; Tab and the layout of the panel beside the image.
#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "app/viewer_state.h"
#include "ui/camera_controls.h"

namespace lueur {
namespace {

bool has_extension(const std::string& path, const std::string& extension) {
  if (path.size() < extension.size()) return false;
  std::string tail = path.substr(path.size() - extension.size());
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == extension;
}

}  // namespace

/// Replaces the buttons ImGui's GLFW back-end polled with the queued ones (see ui/mouse_buttons.h).
void Viewer::deliver_mouse_buttons() {
  MouseButtons& buttons = events_of(window_).buttons;
  buttons.next_frame();
  ImGuiIO& io = ImGui::GetIO();
  for (int b = 0; b < MouseButtons::kCount; ++b) io.MouseDown[b] = buttons.down[static_cast<size_t>(b)];
}

/// An A/B split's divider follows a left drag that starts on it (within a few pixels) outside the panel; true
/// while it does, so that the drag does not also turn the camera.
bool Viewer::drag_divider(const InputEvents& events) {
  const bool left = events.buttons.down[GLFW_MOUSE_BUTTON_LEFT];
  const WindowRect& image = layout_.image;
  if (!left || !right_ || image.width <= 0.0) {
    dragging_divider_ = false;
    return false;
  }
  const double x = events.cursor_x;
  const double divider = image.x + panel_.settings.compare_split * image.width;
  if (!dragging_divider_ && camera_drag_.mode == DragMode::kNone && !ImGui::GetIO().WantCaptureMouse &&
      std::abs(x - divider) <= 6.0)
    dragging_divider_ = true;
  if (!dragging_divider_) return false;
  panel_.settings.compare_split = static_cast<float>(std::clamp((x - image.x) / image.width, 0.0, 1.0));
  return true;
}

void Viewer::handle_input() {
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
  if (drag_divider(events)) {
    end_drag(camera_drag_);
    return;
  }
  if (!panel_.settings.camera) {
    events.scroll = 0.0;
    return;
  }
  CameraSpec& camera = *panel_.settings.camera;
  drag_camera(events, camera);
  if (events.scroll != 0.0 && !ImGui::GetIO().WantCaptureMouse)
    camera = dolly(camera, static_cast<float>(events.scroll));
  events.scroll = 0.0;
  if (!ImGui::GetIO().WantCaptureKeyboard) handle_keys(camera);
}

/// A left drag orbits, a middle or Shift + left drag pans, by the cursor's travel since the press. A drag belongs to
/// the view only when it started outside the panel.
void Viewer::drag_camera(InputEvents& events, CameraSpec& camera) {
  const MouseButtons& buttons = events.buttons;
  const bool left = buttons.down[GLFW_MOUSE_BUTTON_LEFT], middle = buttons.down[GLFW_MOUSE_BUTTON_MIDDLE];
  if (!left && !middle) {
    end_drag(camera_drag_);
    return;
  }
  const bool shift =
      glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  const DragMode mode = middle || shift ? DragMode::kPan : DragMode::kOrbit;
  if (camera_drag_.mode == DragMode::kNone) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    const size_t button = middle ? GLFW_MOUSE_BUTTON_MIDDLE : GLFW_MOUSE_BUTTON_LEFT;
    begin_drag(camera_drag_, mode, camera, buttons.press_x[button], buttons.press_y[button]);
  }
  camera = continue_drag(camera_drag_, mode, camera, events.cursor_x, events.cursor_y, layout_.image.height);
}

/// WASD and Q/E fly; F frames the scene, R goes back to the first view, I and O go inside and outside a closed room.
void Viewer::handle_keys(CameraSpec& camera) {
  const double now = glfwGetTime();
  const float dt = static_cast<float>(std::min(0.1, now - last_key_time_));
  last_key_time_ = now;
  const float speed = 0.4f * (scene_.traced ? scene_.traced->diagonal : 1.0f) * dt;
  const auto down = [&](int key) { return glfwGetKey(window_, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  const float forward = down(GLFW_KEY_W) - down(GLFW_KEY_S), right = down(GLFW_KEY_D) - down(GLFW_KEY_A),
              up = down(GLFW_KEY_E) - down(GLFW_KEY_Q);
  if (forward != 0.0f || right != 0.0f || up != 0.0f) camera = fly(camera, forward * speed, right * speed, up * speed);
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
float Viewer::aspect() const {
  const PixelRect& image = current_layout().image_pixels;
  return image.width > 0 && image.height > 0 ? static_cast<float>(image.width) / static_cast<float>(image.height)
                                             : 1.0f;
}

/// The window shared between the panel (when shown) and the image, as it stands now.
WindowLayout Viewer::current_layout() const {
  int window_width = 0, window_height = 0, fb_width = 0, fb_height = 0;
  glfwGetWindowSize(window_, &window_width, &window_height);
  glfwGetFramebufferSize(window_, &fb_width, &fb_height);
  return lay_out_window(window_width, window_height, fb_width, fb_height, panel_shown_ ? panel_.panel_width : 0.0);
}

/// Tab hides the panel (the image takes the whole window) and shows it again; not while a text field has the keys.
void Viewer::toggle_panel() {
  int& presses = events_of(window_).tab_presses;
  if (!ImGui::GetIO().WantCaptureKeyboard && presses % 2 == 1) panel_shown_ = !panel_shown_;
  presses = 0;
}

}  // namespace lueur
