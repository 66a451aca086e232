// The panel's sections of what is shown and measured: the view and display transform, the noise estimate, the
// A/B split and the statistics.
#include "ui/panel_sections.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "settings/compare.h"
#include "settings/setting_table.h"
#include "ui/panel_widgets.h"
#include "ui/plot_colours.h"

namespace lueur {

void view_section(PanelModel& m) {
  Settings& v = m.settings;
  if (v.camera) {
    // Zoom as a lens does, the eye kept where it is (the wheel dollies instead); a change restarts the accumulation.
    float& fovy = v.camera->fovy_degrees;
    if (ImGui::SliderFloat("Field of view", &fovy, kMinPanelFieldOfView, kMaxPanelFieldOfView, "%.1f deg"))
      fovy = std::clamp(fovy, kMinPanelFieldOfView, kMaxPanelFieldOfView);  // Ctrl+click can type anything
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the camera's vertical field of view, in degrees");
    record_widget(m, "field-of-view");
  }
  // "combined" first, then every layer; the layers that explain reuse are report figures 7 and 8.
  // ... and last the noise view.
  constexpr int kNoiseEntry = kLayerCount + 1;
  const auto name_of = [](int i) {
    return i == 0             ? std::string("combined")
           : i == kNoiseEntry ? std::string("noise")
                              : std::string(kLayerNames[static_cast<size_t>(i - 1)]);
  };
  int current = v.show_noise ? kNoiseEntry : v.layer ? static_cast<int>(*v.layer) + 1 : 0;
  if (ImGui::BeginCombo("View", name_of(current).c_str())) {
    for (int i = 0; i <= kNoiseEntry; ++i)
      if (ImGui::Selectable(name_of(i).c_str(), i == current)) current = i;
    ImGui::EndCombo();
  }
  v.show_noise = current == kNoiseEntry;
  if (current == 0 || v.show_noise)
    v.layer.reset();
  else
    v.layer = static_cast<Layer>(current - 1);
  setting_tooltip("view");
  setting_slider("Exposure (stops)", "exposure", v.display.exposure, "%.2f");
  enum_combo("Tone map", kToneMapNames, v.display.tonemap);
  setting_tooltip("tonemap");
}

/// Each pass's estimated relMSE and the combined image's, and how they fell with time on log-log axes.
void noise_section(const PanelModel& m) {
    const auto line = [&](size_t k, const char* name, const NoiseEstimate& e) {
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kPlotColours[k]), "%-6s", name);
    ImGui::SameLine();
    if (e.known)
      ImGui::Text("%.3g  (variance ~ frames^-%.2f)", e.rel_mse, e.exponent);
    else
      ImGui::TextUnformatted("not known yet");
  };
  for (int p = 0; p < kPassCount; ++p)
    if (m.settings.render.enabled[static_cast<size_t>(p)])
      line(static_cast<size_t>(p), std::string(kPassNames[static_cast<size_t>(p)]).c_str(),
           m.noise.passes[static_cast<size_t>(p)]);
  line(kPassCount, "image", m.noise.image);
  setting_tooltip("target-noise");

  // The plot: log10 seconds across, log10 relMSE up, one line per pass and the image's in white.
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 110.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("noise-plot", size);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(120, 120, 120, 255));
  double t0 = 1e30, t1 = -1e30, e0 = 1e30, e1 = -1e30;
  for (const NoisePoint& point : m.noise_history)
    for (const double e : point.rel_mse)
      if (e > 0.0 && point.seconds > 0.0) {
        t0 = std::min(t0, std::log10(point.seconds));
        t1 = std::max(t1, std::log10(point.seconds));
        e0 = std::min(e0, std::log10(e));
        e1 = std::max(e1, std::log10(e));
      }
  if (!(t1 > t0) || !(e1 >= e0)) return;
  e0 = std::floor(e0);
  e1 = std::max(std::ceil(e1), e0 + 1.0);
  const auto at = [&](double seconds, double e) {
    const float x = static_cast<float>((std::log10(seconds) - t0) / (t1 - t0));
    const float y = static_cast<float>((std::log10(e) - e0) / (e1 - e0));
    return ImVec2(origin.x + 4.0f + x * (size.x - 8.0f), origin.y + size.y - 4.0f - y * (size.y - 8.0f));
  };
  for (size_t k = 0; k <= kPassCount; ++k) {
    ImVec2 previous;
    bool has_previous = false;
    for (const NoisePoint& point : m.noise_history) {
      if (!(point.rel_mse[k] > 0.0) || !(point.seconds > 0.0)) {
        has_previous = false;
        continue;
      }
      const ImVec2 here = at(point.seconds, point.rel_mse[k]);
      if (has_previous) draw->AddLine(previous, here, kPlotColours[k], k == kPassCount ? 2.0f : 1.0f);
      previous = here;
      has_previous = true;
    }
  }
  char label[64];
  std::snprintf(label, sizeof label, "1e%.0f", e1);
  draw->AddText(ImVec2(origin.x + 3.0f, origin.y + 2.0f), IM_COL32(170, 170, 170, 255), label);
  std::snprintf(label, sizeof label, "1e%.0f   %.2g s .. %.2g s (log-log)", e0, std::pow(10.0, t0), std::pow(10.0, t1));
  draw->AddText(ImVec2(origin.x + 3.0f, origin.y + size.y - 16.0f), IM_COL32(170, 170, 170, 255), label);
}

/// The A/B split: which setting its right side changes and to what, the divider, and each side's error and time.
void compare_section(PanelModel& m) {
  Settings& v = m.settings;
  if (v.compare != m.compare_shown) {  // set or cleared elsewhere (command line, view file, the viewer): show it
    m.compare_shown = v.compare;
    const size_t equals = v.compare.find('=');
    if (equals != std::string::npos) {
      m.compare_name = v.compare.substr(0, equals);
      m.compare_value = v.compare.substr(equals + 1);
    }
  }
  if (ImGui::BeginCombo("Setting", m.compare_name.empty() ? "(none)" : m.compare_name.c_str())) {
    for (const std::string_view option : comparable_settings())
      if (ImGui::Selectable(std::string(option).c_str(), option == m.compare_name)) {
        m.compare_name = std::string(option);
        m.compare_value = setting_text(v, option).value_or("");  // the current value, to be edited
      }
    ImGui::EndCombo();
  }
  setting_tooltip("compare");
  char value[128];
  std::snprintf(value, sizeof value, "%s", m.compare_value.c_str());
  if (ImGui::InputText("Right side's value", value, sizeof value)) m.compare_value = value;
  if (ImGui::Button("Compare") && !m.compare_name.empty()) v.compare = m.compare_name + "=" + m.compare_value;
  ImGui::SameLine();
  if (ImGui::Button("Stop comparing")) v.compare.clear();
  if (!m.comparing) return;
  setting_slider("Divider", "compare-split", v.compare_split, "%.2f");
  const auto side = [](const char* which, const NoiseEstimate& e, double seconds) {
    if (e.known)
      ImGui::Text("%s: relMSE %.3g after %.1f s; x s = %.3g", which, e.rel_mse, seconds, e.rel_mse * seconds);
    else
      ImGui::Text("%s: %.1f s, relMSE not known yet", which, seconds);
  };
  side("left ", m.noise.image, m.stats.seconds);
  side("right", m.right_noise, m.right_stats.seconds);
  ImGui::TextDisabled("relMSE x s: the error after one second of tracing (lower is better)");
}

void statistics_section(const PanelModel& m) {
  const TracerStats& s = m.stats;
  ImGui::Text("%s: %zu triangles, %zu emitters", m.scene_name.c_str(), m.triangles, m.emitters);
  ImGui::Text("Resolution %d x %d%s", m.film_width * m.preview_divisor, m.film_height * m.preview_divisor,
              m.preview_divisor > 1 ? " (preview)" : "");
  ImGui::Text("Frames %llu  (samples per pixel %llu)", static_cast<unsigned long long>(s.frames),
              static_cast<unsigned long long>(s.frames));
  ImGui::Text("Elapsed %.2f s, last frame %.1f ms", s.seconds, 1e3 * s.last_frame_seconds);
  ImGui::Text("%.2f Mrays/s", s.mrays_per_second());
  if (s.frames_before_repeat > 0 && s.frames >= s.frames_before_repeat)
    ImGui::TextWrapped("Stopped: each pixel's sample sequence starts over here at these ray counts");
  if (s.l2_bounce_hits > 0) {
    const auto share = [&](uint64_t n) {
      return 100.0 * static_cast<double>(n) / static_cast<double>(s.l2_bounce_hits);
    };
    ImGui::Text("L2: %.1f%% of bounce hits reused L1", share(s.l2_reused));
    if (s.cache.bytes > 0) {
      ImGui::Text("L1 store: %.1f%% of hits, %.1f%% recomputed", share(s.l2_cached),
                  share(s.l2_bounce_hits - s.l2_reused - s.l2_cached));
      ImGui::Text("L1 store: %llu cells, %.1f MiB%s", static_cast<unsigned long long>(s.cache.cells),
                  static_cast<double>(s.cache.bytes) / (1 << 20), s.cache.full ? " (full)" : "");
      if (s.served.total > 0)
        ImGui::Text("Serving cells: median %u samples, 10%% %u", s.served.percentile(0.5), s.served.percentile(0.1));
    }
    if (s.ln_lookups > 0) {
      const auto ln_share = [&](uint64_t n) {
        return 100.0 * static_cast<double>(n) / static_cast<double>(s.ln_lookups);
      };
      ImGui::Text("Ln's L1: %.0f%% screen, %.0f%% store, %.0f%% traced", ln_share(s.ln_reused), ln_share(s.ln_cached),
                  ln_share(s.ln_lookups - s.ln_reused - s.ln_cached));
    }
    if (s.ln_ended > 0)
      ImGui::Text("Ln's paths ended by the store: %.0f%%",
                  100.0 * static_cast<double>(s.ln_ended) / static_cast<double>(s.ln_paths));
    ImGui::Text("L2 time %.2f s", s.l2_seconds);
  }
  if (m.display_fps > 0.0) ImGui::Text("Display %.0f frames/s", m.display_fps);
}

}  // namespace lueur
