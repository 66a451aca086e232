// The pixel inspector: the panel section that reads out the pixel under the mouse (or the one pinned with a right
// click) as the accumulation converges, and the marker on the pinned pixel. Depends on ImGui and the panel's model.
#pragma once

#include "ui/panel.h"

namespace lueur {

/// Adds the pinned pixel's values to the model's history when its frame count moved on (a lower count: the
/// accumulation restarted, and the history with it); clears the history when no pixel is pinned.
void record_probe(PanelModel& model);

/// What the "Pixel" section calls a layer (the names of --view, said the way the report says them); empty for the
/// layers it does not list as light (the reuse shares, the store's cells).
const char* pixel_layer_label(Layer layer);

/// The "Pixel" section: the image's linear value at the inspected pixel and each rendered layer's average there.
void pixel_section(const PanelModel& model);

/// Outlines the view rectangle (x0, y0)-(x1, y1) (window coordinates) that one film pixel covers, with a margin so
/// that a single screen pixel stays visible. Call between ImGui::NewFrame and ImGui::Render.
void draw_pixel_marker(float x0, float y0, float x1, float y1);

}  // namespace lueur
