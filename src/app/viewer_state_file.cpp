// Frame pacing, the display's frame statistics, and the JSON state file: the window's camera, settings, frame counts,
// timings, the probed pixel, the message and the panel's widgets, which the window test reads (--state-file).
#include <algorithm>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/viewer_state.h"
#include "core/atomic_file.h"
#include "settings/view_file.h"

namespace lueur {

void Viewer::record_frame_time(ViewerClock::time_point frame_start) {
  if (previous_frame_start_ != ViewerClock::time_point{}) {
    // The interval between frames, as the user sees it (pacing included), over the last 600 frames.
    if (frame_intervals_ms_.size() == 600) frame_intervals_ms_.erase(frame_intervals_ms_.begin());
    frame_intervals_ms_.push_back(1e3 * seconds_between(previous_frame_start_, frame_start));
  }
  previous_frame_start_ = frame_start;
  const double seconds = seconds_between(frame_start, ViewerClock::now());
  frame_seconds_ = frame_seconds_ == 0.0 ? seconds : 0.9 * frame_seconds_ + 0.1 * seconds;
  panel_.display_fps = frame_seconds_ > 0.0 ? 1.0 / frame_seconds_ : 0.0;
}

/// Without a working vsync (Xvfb, some drivers) the loop would spin; cap it at the monitor's refresh rate.
void Viewer::pace(ViewerClock::time_point frame_start) const {
  const GLFWvidmode* mode = glfwGetVideoMode(glfwGetPrimaryMonitor());
  const double refresh = mode && mode->refreshRate > 0 ? mode->refreshRate : 60.0;
  const double left = 1.0 / refresh - seconds_between(frame_start, ViewerClock::now());
  if (left > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(left));
}

void Viewer::write_state_file() const {
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

}  // namespace lueur
