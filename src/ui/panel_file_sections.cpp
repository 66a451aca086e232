// The panel's sections of control and files: pause, limits and the camera's buttons; scenes, images and views;
// and the list of what the mouse and keys do.
#include "ui/panel_sections.h"

#include <algorithm>
#include <cstdio>

#include "settings/setting_table.h"
#include "ui/panel_widgets.h"

namespace lueur {

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

}  // namespace lueur
