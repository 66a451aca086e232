// The panel's sections of what is rendered: the passes and their weights, and how each is sampled.
#include "ui/panel_sections.h"

#include <algorithm>

#include "integrator/indirect_light.h"
#include "settings/setting_table.h"
#include "ui/panel_widgets.h"

namespace lueur {

void passes_section(PanelModel& m) {
  Settings& v = m.settings;
  static const char* const kLabels[kPassCount] = {"Le  (emission seen)", "L1  (direct light)",
                                                  "L2  (one-bounce indirect)", "AO  (ambient occlusion)",
                                                  "Ln  (further bounces)"};
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
  record_widget(m, "preset-report");
  // The full solution: every light pass at weight 1, the further bounces on, AO (no light) off.
  if (ImGui::Button("Physical (Le + L1 + L2 + Ln, all 1)", ImVec2(full_width, 0.0f))) {
    v.weights = kPhysicalWeights;
    v.render.enabled = {true, true, true, false, true};
  }
  record_widget(m, "preset-physical");
}

namespace {

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

}  // namespace

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
  setting_slider("Ln paths", "ln-rays", r.ln_rays);
  setting_slider("Max bounces", "max-bounces", r.max_bounces);
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

}  // namespace lueur
