// The panel's building blocks (ui/panel_widgets.h).
#include "ui/panel_widgets.h"

#include <algorithm>
#include <cmath>

#include "settings/setting_table.h"

namespace lueur {

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

}  // namespace lueur
