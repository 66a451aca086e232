// The Dear ImGui control panel: edits the settings in place (within the limits of the settings table) and reports
// the buttons pressed. It draws with whatever
// ImGui back-end is running (the window's GLFW one, or none for a headless screenshot) and knows nothing of the
// tracer thread: the caller applies the edited state.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "film/noise_estimate.h"
#include "film/pixel_probe.h"
#include "runtime/progressive_tracer.h"
#include "integrator/traced_scene.h"
#include "settings/settings.h"

namespace lueur {

/// The estimated noise at one moment of an accumulation: each pass's relMSE, then the combined image's (0: unknown).
struct NoisePoint {
  double seconds = 0.0;
  std::array<double, kPassCount + 1> rel_mse{};
};

/// A pinned pixel's values after some frames, for the inspector's plot: each pass's luminance (0 where it is not
/// rendered), then the image's.
struct ProbePoint {
  uint64_t frames = 0;
  std::array<float, kPassCount + 1> luminance{};
};

/// The panel's width when it opens, in window pixels, and the range its right edge can be dragged over.
inline constexpr float kPanelWidth = 340.0f;
inline constexpr float kMinPanelWidth = 240.0f, kMaxPanelWidth = 720.0f;
/// The field-of-view slider's range, in degrees (the command line's --camera takes anything in (0, 180)).
inline constexpr float kMinPanelFieldOfView = 1.0f, kMaxPanelFieldOfView = 150.0f;

struct PanelModel {
  Settings settings;  ///< edited by the widgets
  bool paused = false;
  // Read-only figures.
  TracerStats stats;
  FilmNoise noise;                          ///< the shown film's estimated noise
  bool comparing = false;                   ///< an A/B split is on (settings.compare)
  NoiseEstimate right_noise;                ///< its right side's image estimate
  TracerStats right_stats;                  ///< and that side's figures
  std::string compare_name, compare_value;  ///< the compare section's choice, until applied
  std::string compare_shown;                ///< the comparison those were last taken from
  std::vector<NoisePoint> noise_history;    ///< how it fell since the accumulation began, oldest first
  int film_width = 0, film_height = 0, preview_divisor = 1;
  std::string scene_name;
  size_t triangles = 0, emitters = 0;
  float automatic_ao_radius = 0.0f;  ///< the AO radius used while the setting is 0 (a tenth of the diagonal)
  bool has_light_rig = false;        ///< the scene had no emitter and is lit by the default rig
  bool closed_room = false;          ///< the scene has a view from inside (the caller sets it)
  std::string status;                ///< e.g. "loading bunny.obj: building the BVH (1.2 s)"; empty when idle
  double status_done = -1.0;         ///< the loading stage's share done, shown as a bar; negative: none
  std::vector<std::string> status_stages;  ///< the loading stages finished, with their times
  std::string message;               ///< the last saved path or error
  bool message_is_error = false;
  std::string view_path = "lueur-view.json";  ///< the file "Save view" and "Load view" use
  /// The pixel inspector's pixel (film/pixel_probe.h): under the mouse, or pinned; none before the mouse is over
  /// the image.
  std::optional<PixelProbe> probe;
  bool probe_pinned = false, probe_right_side = false;
  std::vector<ProbePoint> probe_history;  ///< the pinned pixel's, since it was pinned or the accumulation restarted
  std::string scene_path;  ///< the "Scene file" field: the scene shown (empty: the default one), or one typed to open
  double display_fps = 0.0;
  /// Where some widgets were drawn last frame (x0, y0, x1, y1 in window pixels, y down), by name ("pass-l2",
  /// "weight-l1", ...): the window reports them so that tests can click them with synthetic input.
  std::map<std::string, std::array<float, 4>> widget_rects;
  float panel_width = kPanelWidth;  ///< the panel's column, in window pixels
};

struct PanelActions {
  bool reset = false;
  bool save_png = false, save_pfm = false, save_exr = false;
  bool save_view = false, load_view = false;
  bool frame_scene = false, reset_camera = false;
  bool inside_view = false, outside_view = false;  ///< a closed room's views (keys I and O)
  bool open_scene = false;    ///< open the scene named in the "Scene file" field
  bool reload_scene = false;  ///< read the scene shown again from its files (key F5)
};

/// Keeps a plot's history bounded: once it holds `limit` points, every other one goes (its start and its shape stay).
template <typename Point>
void thin_history(std::vector<Point>& history, size_t limit = 512) {
  if (history.size() < limit) return;
  size_t kept = 0;
  for (size_t i = 0; i < history.size(); i += 2) history[kept++] = history[i];
  history.resize(kept);
}

/// Adds `noise` at `seconds` to the model's history when it is known and the history's last point is older.
void record_noise(PanelModel& model, const FilmNoise& noise, double seconds);

/// Sets the panel's figures about the scene being traced: name, triangle and emitter counts, automatic AO radius.
void describe_scene(PanelModel& model, const TracedScene& traced);

/// Draws the panel as one ImGui window: a column down the left of the display, `height` tall and
/// `model.panel_width` wide (dragging its right edge changes that width). Opaque beside the image; translucent when
/// `over_image` (a window too narrow for both). Call between ImGui::NewFrame and Render.
PanelActions draw_panel(PanelModel& model, float height, bool over_image = false);

}  // namespace lueur
