// The window's two tracers: the panel's settings and camera go in (a change restarts the accumulation), and each
// side's newest snapshot comes out, never waiting for a frame. The second tracer renders an A/B split's right side.
#include <exception>

#include "app/viewer_state.h"
#include "settings/compare.h"

namespace lueur {

void Viewer::apply_to_tracer() {
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
    if (!restart_pending_) restart_time_ = ViewerClock::now();
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
void Viewer::apply_to_right_tracer() {
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

/// Swaps in each side's newest finished frame, if there is one, and updates what depends on it.
void Viewer::take_snapshots() {
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
}

}  // namespace lueur
