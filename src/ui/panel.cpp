// The panel's widgets, grouped as the report explains the image: passes and weights, light sampling, L2 and its
// reuse, AO, what to view, the display transform, statistics, and files.
#include "ui/panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "integrator/indirect_light.h"
#include "settings/compare.h"
#include "settings/setting_table.h"
#include "ui/pixel_inspector.h"
#include "ui/plot_colours.h"

namespace lueur {
namespace {

template <size_t N>
bool enum_combo(const char* label, const std::array<std::string_view, N>& names, int& value) {
  bool changed = false;
  const std::string current(names[static_cast<size_t>(value)]);
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (size_t i = 0; i < N; ++i) {
      const std::string name(names[i]);
      const bool selected = static_cast<int>(i) == value;
      if (ImGui::Selectable(name.c_str(), selected)) {
        changed = value != static_cast<int>(i);
        value = static_cast<int>(i);
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  return changed;
}

template <typename Enum, size_t N>
bool enum_combo(const char* label, const std::array<std::string_view, N>& names, Enum& value) {
  int v = static_cast<int>(value);
  const bool changed = enum_combo(label, names, v);
  value = static_cast<Enum>(v);
  return changed;
}

/// The setting's help as the last widget's tooltip.
void setting_tooltip(std::string_view name) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", std::string(setting_info(name).help).c_str());
}

/// A slider over the setting's panel span (settings table); a value typed in (Ctrl+click) stays within the
/// setting's full range, as on the command line.
bool setting_slider(const char* label, std::string_view name, int& value) {
  const SettingInfo& info = setting_info(name);
  const bool changed =
      ImGui::SliderInt(label, &value, static_cast<int>(info.slider->min), static_cast<int>(info.slider->max));
  setting_tooltip(name);
  value = std::clamp(value, static_cast<int>(info.range->min), static_cast<int>(info.range->max));
  return changed;
}

bool setting_slider(const char* label, std::string_view name, float& value, const char* format) {
  const SettingInfo& info = setting_info(name);
  const bool changed = ImGui::SliderFloat(label, &value, static_cast<float>(info.slider->min),
                                          static_cast<float>(info.slider->max), format);
  setting_tooltip(name);
  if (!std::isfinite(value)) value = static_cast<float>(info.slider->min);
  value = std::clamp(value, static_cast<float>(info.range->min), static_cast<float>(info.range->max));
  return changed;
}

void record_widget(PanelModel& m, const std::string& name) {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  m.widget_rects[name] = {lo.x, lo.y, hi.x, hi.y};
}

void passes_section(PanelModel& m) {
  Settings& v = m.settings;
  static const char* const kLabels[kPassCount] = {"Le  (emission seen)", "L1  (direct light)",
                                                  "L2  (one-bounce indirect)", "AO  (ambient occlusion)"};
  for (int p = 0; p < kPassCount; ++p) {
    const size_t i = static_cast<size_t>(p);
    ImGui::PushID(p);
    ImGui::Checkbox("##on", &v.render.enabled[i]);
    record_widget(m, "pass-" + std::string(kPassNames[i]));
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.0f);
    setting_slider("##weight", "weights", v.weights[i], "%.2f");
    record_widget(m, "weight-" + std::string(kPassNames[i]));
    ImGui::SameLine();
    ImGui::TextUnformatted(kLabels[p]);
    ImGui::PopID();
  }
  // One preset per line: side by side they do not fit the panel's width.
  const float full_width = ImGui::GetContentRegionAvail().x;
  if (ImGui::Button("Report (Le 1, L1 0.6, L2 0.4)", ImVec2(full_width, 0.0f))) v.weights = kReportWeights;
  if (ImGui::Button("Physical (all 1)", ImVec2(full_width, 0.0f))) v.weights = {1.0f, 1.0f, 1.0f, 1.0f};
}

/// The AO radius: automatic (the setting 0, shown as the radius it stands for) or typed in world units.
void ao_radius_widgets(PanelModel& m) {
  RenderSettings& r = m.settings.render;
  const float automatic_radius = m.automatic_ao_radius;
  bool automatic = r.ao_radius <= 0.0f;
  if (ImGui::Checkbox("Automatic AO radius", &automatic)) r.ao_radius = automatic ? 0.0f : automatic_radius;
  record_widget(m, "ao-automatic");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a tenth of the scene's bounding-box diagonal");
  if (automatic) {
    ImGui::Text("AO radius %.4g (automatic)", automatic_radius);
    return;
  }
  ImGui::InputFloat("AO radius", &r.ao_radius, 0.0f, 0.0f, "%.4g");
  setting_tooltip("ao-radius");
  if (!(r.ao_radius > 0.0f)) r.ao_radius = 0.0f;  // 0, negative or NaN: back to automatic
  r.ao_radius = std::min(r.ao_radius, static_cast<float>(setting_info("ao-radius").range->max));
}

/// The store's cell size: automatic (the setting 0, shown as the size it stands for at this image height) or set.
void cache_cell_widgets(PanelModel& m) {
  RenderSettings& r = m.settings.render;
  bool automatic = r.cache_cell_pixels <= 0.0f;
  if (ImGui::Checkbox("Automatic store cell", &automatic))
    r.cache_cell_pixels = automatic ? 0.0f : r.automatic_cache_cell_pixels();
  record_widget(m, "cache-cell-automatic");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("2 x sqrt(image height / 128) pixels: 2 at 128 lines, 4 at 512");
  if (automatic) {
    ImGui::Text("Store cell %.2f px (automatic)", r.automatic_cache_cell_pixels());
    return;
  }
  setting_slider("Store cell (px)", "cache-cell-pixels", r.cache_cell_pixels, "%.1f");
  if (!(r.cache_cell_pixels > 0.0f)) r.cache_cell_pixels = 0.0f;  // 0 or less: back to automatic
}

void sampling_section(PanelModel& m) {
  Settings& v = m.settings;
  RenderSettings& r = v.render;
  enum_combo("Sampler", kSamplerKindNames, r.sampler);
  setting_tooltip("sampler");
  enum_combo("Light sampling", kLightStrategyNames, r.lights);
  setting_tooltip("lights");
  setting_slider("Le camera rays", "le-rays", r.le_rays);
  setting_slider("L1 shadow rays", "l1-rays", r.l1_rays);
  setting_slider("Blinn-Phong K", "blinn-k", r.blinn_k, "%.2f");
  setting_slider("L2 bounce rays", "l2-rays", r.l2_rays);
  enum_combo("L2 reuse", kReuseModeNames, r.reuse);
  setting_tooltip("reuse");
  setting_slider("Recompute ratio", "recompute-ratio", r.recompute_ratio, "%.3f");
  ImGui::Checkbox("Reuse diffuse L1 only", &r.reuse_diffuse_only);
  setting_tooltip("reuse-diffuse-only");
  if (uses_cache(r.reuse)) {
    cache_cell_widgets(m);
    setting_slider("Store cap (MiB)", "cache-mb", r.cache_mb);
  }
  setting_slider("AO rays", "ao-rays", r.ao_rays);
  ao_radius_widgets(m);
  ImGui::Checkbox("Smooth normals", &v.smooth_normals);  // the viewer prepares the scene again
  setting_tooltip("smooth-normals");
  ImGui::Checkbox("Head-light", &r.camera_light);
  setting_tooltip("camera-light");
  // The default light rig: only scenes without emitters have one, but turning it on again must stay possible.
  if (m.has_light_rig || !v.light_rig) {
    ImGui::Checkbox("Default light rig", &v.light_rig);
    setting_tooltip("light-rig");
    if (v.light_rig) setting_slider("Rig brightness", "light-rig-scale", v.light_rig_scale, "%.2f");
  }
  int seed = static_cast<int>(r.seed & 0x7fffffff);
  if (ImGui::InputInt("Seed", &seed) && seed >= 0) r.seed = static_cast<uint64_t>(seed);
  setting_tooltip("seed");
}

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
    }
    ImGui::Text("L2 time %.2f s", s.l2_seconds);
  }
  if (m.display_fps > 0.0) ImGui::Text("Display %.0f frames/s", m.display_fps);
}

void control_section(PanelModel& m, PanelActions& actions) {
  enum_combo("Accelerator", kAccelKindNames, m.settings.accel);  // the viewer builds the scene's structure again
  setting_tooltip("accel");
  if (ImGui::Button(m.paused ? "Resume" : "Pause")) m.paused = !m.paused;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) actions.reset = true;
  ImGui::SameLine();
  int limit = static_cast<int>(std::min<uint64_t>(m.settings.frame_limit, 1000000));
  ImGui::SetNextItemWidth(100.0f);
  if (ImGui::InputInt("Frame limit", &limit, 0, 0)) m.settings.frame_limit = static_cast<uint64_t>(std::max(0, limit));
  setting_tooltip("frame-limit");
  ImGui::SetNextItemWidth(100.0f);
  ImGui::InputFloat("Time limit (s)", &m.settings.time_limit, 0.0f, 0.0f, "%.1f");
  setting_tooltip("time-limit");
  if (!(m.settings.time_limit >= 0.0f)) m.settings.time_limit = 0.0f;  // negative or NaN: no limit
  m.settings.time_limit = std::min(m.settings.time_limit, static_cast<float>(setting_info("time-limit").range->max));
  ImGui::SetNextItemWidth(100.0f);
  ImGui::InputFloat("Stop at noise", &m.settings.target_noise, 0.0f, 0.0f, "%.2g");
  setting_tooltip("target-noise");
  if (!(m.settings.target_noise >= 0.0f)) m.settings.target_noise = 0.0f;
  if (ImGui::Button("Frame scene (F)")) actions.frame_scene = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset view (R)")) actions.reset_camera = true;
  if (m.closed_room) {
    if (ImGui::Button("Inside the room (I)")) actions.inside_view = true;
    ImGui::SameLine();
    if (ImGui::Button("Outside (O)")) actions.outside_view = true;
  }
}

void files_section(PanelModel& m, PanelActions& actions) {
  char scene[1024];
  std::snprintf(scene, sizeof scene, "%s", m.scene_path.c_str());
  if (ImGui::InputTextWithHint("Scene file", "the default scene", scene, sizeof scene)) m.scene_path = scene;
  if (ImGui::Button("Open")) actions.open_scene = true;
  ImGui::SameLine();
  if (ImGui::Button("Reload (F5)")) actions.reload_scene = true;
  record_widget(m, "reload-scene");
  ImGui::SameLine();
  ImGui::Checkbox("Reload when saved", &m.settings.watch);
  setting_tooltip("watch");
  if (ImGui::Button("Save PNG")) actions.save_png = true;
  ImGui::SameLine();
  if (ImGui::Button("Save PFM")) actions.save_pfm = true;
  ImGui::SameLine();
  if (ImGui::Button("Save EXR")) actions.save_exr = true;
  char path[512];
  std::snprintf(path, sizeof path, "%s", m.view_path.c_str());
  if (ImGui::InputText("View file", path, sizeof path)) m.view_path = path;
  if (ImGui::Button("Save view")) actions.save_view = true;
  ImGui::SameLine();
  if (ImGui::Button("Load view")) actions.load_view = true;
}

/// What the mouse and the keys do in the window (the README's list), for a user who has not read it.
void keys_section() {
  static const char* const kLines[][2] = {
      {"left drag", "orbit"},
      {"middle drag, Shift + left drag", "pan"},
      {"wheel", "dolly"},
      {"W A S D, Q E", "fly (forward, left, back, right, down, up)"},
      {"F", "frame the scene"},
      {"R", "back to the first view"},
      {"I, O", "inside, outside a closed room"},
      {"F5", "read the scene again from its files"},
      {"right click", "pin the inspected pixel (again: let it go)"},
      {"Tab", "hide or show this panel"},
      {"drop a file", "an OBJ opens it, a view .json applies it"},
  };
  if (!ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingStretchProp)) return;
  for (const auto& [keys, action] : kLines) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", keys);
    ImGui::TableNextColumn();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", action);
    ImGui::PopStyleColor();
  }
  ImGui::EndTable();
}

}  // namespace

void record_noise(PanelModel& model, const FilmNoise& noise, double seconds) {
  NoisePoint point;
  point.seconds = seconds;
  bool known = false;
  for (size_t p = 0; p < kPassCount; ++p)
    if (noise.passes[p].known) {
      point.rel_mse[p] = noise.passes[p].rel_mse;
      known = true;
    }
  if (noise.image.known) point.rel_mse[kPassCount] = noise.image.rel_mse;
  if (!known || (!model.noise_history.empty() && model.noise_history.back().seconds >= seconds)) return;
  thin_history(model.noise_history);
  model.noise_history.push_back(point);
}

void describe_scene(PanelModel& m, const TracedScene& traced) {
  m.scene_name = traced.scene.name;
  m.triangles = traced.scene.triangles.size();
  m.emitters = traced.lights.size();
  m.automatic_ao_radius = ambient_occlusion_radius(traced, RenderSettings{});
  m.has_light_rig = traced.scene.rig_begin != Scene::kNoRig;
}

PanelActions draw_panel(PanelModel& m, float height, bool over_image) {
  PanelActions actions;
  // A column docked to the left edge, full height; only its width is the user's (the right edge drags).
  m.panel_width = std::clamp(m.panel_width, kMinPanelWidth, kMaxPanelWidth);
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(m.panel_width, height), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kMinPanelWidth, height), ImVec2(kMaxPanelWidth, height));
  ImGui::SetNextWindowBgAlpha(over_image ? 0.85f : 1.0f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
  if (!ImGui::Begin("Lueur", nullptr, flags)) {
    ImGui::End();
    return actions;
  }
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);  // leave room for the labels on the right
  ImGui::TextDisabled("Tab hides the panel; keys: last section");
  if (!m.status.empty()) ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.3f, 1.0f), "%s", m.status.c_str());
  if (!m.message.empty()) {
    const ImVec4 colour = m.message_is_error ? ImVec4(1.0f, 0.35f, 0.3f, 1.0f) : ImVec4(0.6f, 0.9f, 0.6f, 1.0f);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", m.message.c_str());
    ImGui::PopStyleColor();
  }
  if (ImGui::CollapsingHeader("Passes", ImGuiTreeNodeFlags_DefaultOpen)) passes_section(m);
  if (ImGui::CollapsingHeader("Sampling", ImGuiTreeNodeFlags_DefaultOpen)) sampling_section(m);
  if (ImGui::CollapsingHeader("View and display", ImGuiTreeNodeFlags_DefaultOpen)) view_section(m);
  if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) statistics_section(m);
  if (ImGui::CollapsingHeader("Pixel", ImGuiTreeNodeFlags_DefaultOpen)) pixel_section(m);
  if (ImGui::CollapsingHeader("Noise (estimated relMSE)", ImGuiTreeNodeFlags_DefaultOpen)) noise_section(m);
  if (ImGui::CollapsingHeader("Compare (A/B split)", m.settings.compare.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    compare_section(m);
  if (ImGui::CollapsingHeader("Control", ImGuiTreeNodeFlags_DefaultOpen)) control_section(m, actions);
  if (ImGui::CollapsingHeader("Files", ImGuiTreeNodeFlags_DefaultOpen)) files_section(m, actions);
  if (ImGui::CollapsingHeader("Mouse and keys")) keys_section();
  ImGui::PopItemWidth();
  record_widget(m, "panel-end");
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  m.widget_rects["panel"] = {pos.x, pos.y, pos.x + size.x, pos.y + size.y};
  m.panel_width = size.x;  // the width the user dragged it to, for the next layout
  ImGui::End();
  return actions;
}

}  // namespace lueur
