// The colours the panel's plots give each pass (Le, L1, L2, AO, Ln) and the combined image, so that the noise plot and
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
    IM_COL32(255, 150, 90, 255),   // Ln
    IM_COL32(255, 255, 255, 255),  // the image
};
// An entry left out (as Ln's once was) would leave the last one zero: the image's line drawn transparent.
static_assert(
    [] {
      for (const ImU32 colour : kPlotColours)
        if (colour == 0) return false;
      return true;
    }(),
    "a plot colour for every pass and the image");

}  // namespace lueur
