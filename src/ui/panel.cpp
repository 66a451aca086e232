// The panel: a column of sections, grouped as the report explains the image (passes and weights, light sampling, L2
// and its reuse, AO, what to view, the display transform, statistics, the pixel, noise, control and files), each
// drawn by its own file (ui/panel_sections.h); and what the viewer tells it of the scene and the noise.
#include "ui/panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "integrator/indirect_light.h"
#include "ui/panel_sections.h"
#include "ui/panel_widgets.h"
#include "ui/pixel_inspector.h"

namespace lueur {

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
  if (!m.status.empty()) {
    for (const std::string& stage : m.status_stages) ImGui::TextDisabled("  %s", stage.c_str());
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.85f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", m.status.c_str());  // a long path must not push the time out of the panel
    ImGui::PopStyleColor();
    if (m.status_done >= 0.0) ImGui::ProgressBar(static_cast<float>(m.status_done), ImVec2(-1.0f, 0.0f));
  }
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
