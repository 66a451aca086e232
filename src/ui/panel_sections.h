// The panel's sections, each drawing its widgets into the open panel window (draw_panel, ui/panel.cpp):
//   panel_render_sections.cpp  passes and weights, sampling (rays, light choice, reuse, the L1 store, AO, rig, seed)
//   panel_view_sections.cpp    view and display, noise, the A/B split, statistics
//   panel_file_sections.cpp    control (pause, limits, camera buttons), files, mouse and keys
#pragma once

#include "ui/panel.h"

namespace lueur {

void passes_section(PanelModel& m);
void sampling_section(PanelModel& m);
void view_section(PanelModel& m);
void noise_section(const PanelModel& m);
void compare_section(PanelModel& m);
void statistics_section(const PanelModel& m);
void control_section(PanelModel& m, PanelActions& actions);
void files_section(PanelModel& m, PanelActions& actions);
void keys_section();

}  // namespace lueur
