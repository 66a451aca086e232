// The pixel inspector's section and marker (see pixel_inspector.h).
#include "ui/pixel_inspector.h"

#include <imgui.h>

namespace lueur {
namespace {

/// What each layer is called in the section (the names of --view, said the way the report says them).
constexpr std::array<const char*, kLayerCount> kLayerLabels = {
    "Le", "L1", "L2", "AO", "L2 (screen L1)", "L2 (recomputed)", "", "L1 diffuse", "L2 (stored L1)", ""};

void rgb_row(const char* label, const Vec3& v) {
  ImGui::Text("%-15s %8.4g %8.4g %8.4g", label, static_cast<double>(v.r), static_cast<double>(v.g),
              static_cast<double>(v.b));
}

}  // namespace

void pixel_section(const PanelModel& m) {
  if (!m.probe) {
    ImGui::TextDisabled("Point at the image; a right click pins the pixel");
    return;
  }
  const PixelProbe& p = *m.probe;
  ImGui::Text("Pixel %d, %d%s%s, %llu frame%s", p.pixel.x, p.pixel.y, m.probe_pinned ? " (pinned)" : "",
              m.probe_right_side ? " of the right side" : "", static_cast<unsigned long long>(p.frames),
              p.frames == 1 ? "" : "s");
  if (m.preview_divisor > 1) ImGui::TextDisabled("(a preview at 1/%d of the size)", m.preview_divisor);
  ImGui::TextDisabled("%-15s %8s %8s %8s", "linear", "R", "G", "B");
  rgb_row("image", p.combined);
  for (size_t l = 0; l < static_cast<size_t>(kLayerCount); ++l) {
    if (!p.layers[l] || kLayerLabels[l][0] == '\0') continue;
    rgb_row(kLayerLabels[l], *p.layers[l]);
  }
  // The reuse fractions are shares of the bounce hits, not light.
  if (const std::optional<Vec3>& shares = p.layers[static_cast<size_t>(Layer::kReuseFraction)])
    ImGui::Text("L2's L1: %.0f%% screen, %.0f%% store, %.0f%% recomputed", 100.0 * shares->r, 100.0 * shares->g,
                100.0 * shares->b);
  if (m.probe_pinned) ImGui::TextDisabled("A right click in the image lets it go");
}

void draw_pixel_marker(float x0, float y0, float x1, float y1) {
  ImDrawList* list = ImGui::GetForegroundDrawList();
  const float margin = 3.0f;
  const ImVec2 lo(x0 - margin, y0 - margin), hi(x1 + margin, y1 + margin);
  list->AddRect(ImVec2(lo.x - 1.0f, lo.y - 1.0f), ImVec2(hi.x + 1.0f, hi.y + 1.0f), IM_COL32(0, 0, 0, 255));
  list->AddRect(lo, hi, IM_COL32(255, 230, 0, 255));
}

}  // namespace lueur
