// The panel's building blocks: a combo over an enum's name table, sliders bounded by the settings table with the
// setting's help as tooltip, and the record of a widget's rectangle (for the state file the window test reads).
// Shared by the panel's sections (ui/panel_sections.h).
#pragma once

#include <imgui.h>

#include <array>
#include <string>
#include <string_view>

#include "ui/panel.h"

namespace lueur {

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
void setting_tooltip(std::string_view name);

/// A slider over the setting's panel span (settings table); a value typed in (Ctrl+click) stays within the
/// setting's full range, as on the command line.
bool setting_slider(const char* label, std::string_view name, int& value);
bool setting_slider(const char* label, std::string_view name, float& value, const char* format);

/// Keeps the last widget's rectangle under `name` in the model's widget_rects.
void record_widget(PanelModel& m, const std::string& name);

}  // namespace lueur
