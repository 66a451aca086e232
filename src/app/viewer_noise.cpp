// The noise estimate of each side of the window, its history since the accumulation began, the pause once the image
// is as quiet as --target-noise asks, and the word that an accumulation stopped at the end of its sample sequences.
#include <cstdio>

#include "app/viewer_state.h"

namespace lueur {

/// The shown film's noise estimate, its history since the accumulation began, and the stop at a target noise.
void Viewer::update_noise() {
  if (shown_.generation != noise_generation_) {
    noise_generation_ = shown_.generation;
    panel_.noise_history.clear();
    panel_.noise = FilmNoise{};
    noise_estimate_.reset();
    noise_target_met_ = false;
    repeat_reported_ = false;
  }
  if (shown_.preview_divisor != 1) return;
  const Settings& s = panel_.settings;
  panel_.noise = noise_estimate_.update(shown_.film, s.render.enabled, s.weights, s.render.sampler);
  record_noise(panel_, panel_.noise, shown_.stats.seconds);
  const NoiseEstimate& image = panel_.noise.image;
  char text[200];
  if (s.target_noise > 0.0f && image.known && image.rel_mse < s.target_noise && !noise_target_met_) {
    noise_target_met_ = true;
    panel_.paused = true;
    std::snprintf(text, sizeof text, "target noise %g reached after %llu frames, %.1f s: paused",
                  static_cast<double>(s.target_noise), static_cast<unsigned long long>(shown_.film.frames),
                  shown_.stats.seconds);
    set_message(text, false);
  }
  if (shown_.film.frames >= shown_.stats.frames_before_repeat && !repeat_reported_) {
    repeat_reported_ = true;
    std::snprintf(text, sizeof text,
                  "stopped after %llu frames: at these ray counts each pixel's sample sequence starts over here "
                  "(fewer rays per frame go further)",
                  static_cast<unsigned long long>(shown_.film.frames));
    set_message(text, false);
  }
}

/// The right side's estimated error and tracing time, for the panel.
void Viewer::update_right_figures() {
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

}  // namespace lueur
