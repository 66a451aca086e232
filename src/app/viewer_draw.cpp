// Drawing the window's image: the shown film (or the A/B split of both sides) through the display pipelines into the
// rectangle beside the panel; and the pixel inspector, which reads the pixel under the mouse from the film shown.
#include <imgui.h>

#include "app/viewer_state.h"
#include "display/split_view.h"
#include "film/pixel_probe.h"
#include "ui/pixel_inspector.h"

namespace lueur {

void Viewer::draw() {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
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
bool Viewer::split_shown() const {
  return right_ && shown_.film.width > 0 && shown_right_.film.width == shown_.film.width &&
         shown_right_.film.height == shown_.film.height;
}

/// The pixel inspector's pixel: the one under the mouse while it is over the image (the last one while it is over
/// the panel), or the one a right click pinned, outlined. Read from the film shown on that side of an A/B split.
void Viewer::update_probe() {
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

}  // namespace lueur
