// The colours the panel's plots give each pass (Le, L1, L2, AO) and the combined image, so that the noise plot and
// the pixel inspector's plot read alike. Depends on ImGui.
#pragma once

#include <imgui.h>

#include <array>

#include "passes/render_settings.h"

namespace lueur {

inline constexpr std::array<ImU32, kPassCount + 1> kPlotColours = {
    IM_COL32(255, 220, 90, 255),   // Le
    IM_COL32(110, 200, 255, 255),  // L1
    IM_COL32(120, 235, 120, 255),  // L2
    IM_COL32(200, 160, 255, 255),  // AO
    IM_COL32(255, 255, 255, 255),  // the image
};

}  // namespace lueur
