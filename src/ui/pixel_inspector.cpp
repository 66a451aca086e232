// The pixel inspector's section and marker (see pixel_inspector.h).
#include "ui/pixel_inspector.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/plot_colours.h"

namespace lueur {
namespace {

/// The pinned pixel's running averages against the frame count (log2 across, linear up): the passes settling.
void convergence_plot(const std::vector<ProbePoint>& history) {
  if (history.size() < 2) return;
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 90.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("pixel-plot", size);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(120, 120, 120, 255));
  const double f0 = std::log2(static_cast<double>(std::max<uint64_t>(history.front().frames, 1)));
  const double f1 = std::max(std::log2(static_cast<double>(history.back().frames)), f0 + 1.0);
  float top = 0.0f;
  for (const ProbePoint& point : history)
    for (const float v : point.luminance) top = std::max(top, v);
  if (!(top > 0.0f) || !std::isfinite(top)) return;
  top *= 1.05f;
  const auto at = [&](const ProbePoint& point, size_t k) {
    const float x = static_cast<float>((std::log2(static_cast<double>(point.frames)) - f0) / (f1 - f0));
    const float y = std::clamp(point.luminance[k] / top, 0.0f, 1.0f);
    return ImVec2(origin.x + 4.0f + x * (size.x - 8.0f), origin.y + size.y - 4.0f - y * (size.y - 8.0f));
  };
  for (size_t k = 0; k < kPlotColours.size(); ++k) {
    // A pass that is not rendered (or gives this pixel nothing) would only draw along the bottom.
    if (std::all_of(history.begin(), history.end(), [k](const ProbePoint& p) { return p.luminance[k] == 0.0f; }))
      continue;
    for (size_t i = 1; i < history.size(); ++i)
      draw->AddLine(at(history[i - 1], k), at(history[i], k), kPlotColours[k], k == kPassCount ? 2.0f : 1.0f);
  }
  char label[96];
  std::snprintf(label, sizeof label, "%.3g", static_cast<double>(top));
  draw->AddText(ImVec2(origin.x + 3.0f, origin.y + 2.0f), IM_COL32(170, 170, 170, 255), label);
  std::snprintf(label, sizeof label, "0   frames %llu .. %llu (log)",
                static_cast<unsigned long long>(history.front().frames),
                static_cast<unsigned long long>(history.back().frames));
  draw->AddText(ImVec2(origin.x + 3.0f, origin.y + size.y - 16.0f), IM_COL32(170, 170, 170, 255), label);
}

void rgb_row(const char* label, const Vec3& v) {
  ImGui::Text("%-15s %8.4g %8.4g %8.4g", label, static_cast<double>(v.r), static_cast<double>(v.g),
              static_cast<double>(v.b));
}

}  // namespace

const char* pixel_layer_label(Layer layer) {
  // A switch, not a table: a layer added to the enum without a label here is a compiler warning, not a null label.
  switch (layer) {
    case Layer::kLe:
      return "Le";
    case Layer::kL1:
      return "L1";
    case Layer::kL2:
      return "L2";
    case Layer::kAo:
      return "AO";
    case Layer::kLn:
      return "Ln";
    case Layer::kL2Reused:
      return "L2 (screen L1)";
    case Layer::kL2Recomputed:
      return "L2 (recomputed)";
    case Layer::kReuseFraction:
      return "";  // shares, not light: a line of its own
    case Layer::kL1Diffuse:
      return "L1 diffuse";
    case Layer::kL2Cached:
      return "L2 (stored L1)";
    case Layer::kCacheCells:
      return "";  // the store's cells in false colour, not light
  }
  return "";
}

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
    const char* label = pixel_layer_label(static_cast<Layer>(l));
    if (!p.layers[l] || label[0] == '\0') continue;
    if (l < static_cast<size_t>(kPassCount)) {  // a pass: in its plot colour
      ImGui::PushStyleColor(ImGuiCol_Text, ImGui::ColorConvertU32ToFloat4(kPlotColours[l]));
      rgb_row(label, *p.layers[l]);
      ImGui::PopStyleColor();
    } else {
      rgb_row(label, *p.layers[l]);
    }
  }
  // The reuse fractions are shares of the bounce hits, not light.
  if (const std::optional<Vec3>& shares = p.layers[static_cast<size_t>(Layer::kReuseFraction)])
    ImGui::Text("L2's L1: %.0f%% screen, %.0f%% store, %.0f%% recomputed", 100.0 * shares->r, 100.0 * shares->g,
                100.0 * shares->b);
  if (!m.probe_pinned) return;
  convergence_plot(m.probe_history);
  ImGui::TextDisabled("A right click in the image lets it go");
}

void record_probe(PanelModel& m) {
  if (!m.probe_pinned || !m.probe) {
    if (!m.probe_pinned) m.probe_history.clear();
    return;
  }
  const PixelProbe& probe = *m.probe;
  std::vector<ProbePoint>& history = m.probe_history;
  if (!history.empty() && probe.frames < history.back().frames) history.clear();  // the accumulation restarted
  if (!history.empty() && probe.frames == history.back().frames) return;
  ProbePoint point;
  point.frames = probe.frames;
  for (size_t p = 0; p < static_cast<size_t>(kPassCount); ++p)
    if (probe.layers[p]) point.luminance[p] = luminance(*probe.layers[p]);
  point.luminance[kPassCount] = luminance(probe.combined);
  thin_history(history);
  history.push_back(point);
}

void draw_pixel_marker(float x0, float y0, float x1, float y1) {
  ImDrawList* list = ImGui::GetForegroundDrawList();
  const float margin = 3.0f;
  const ImVec2 lo(x0 - margin, y0 - margin), hi(x1 + margin, y1 + margin);
  list->AddRect(ImVec2(lo.x - 1.0f, lo.y - 1.0f), ImVec2(hi.x + 1.0f, hi.y + 1.0f), IM_COL32(0, 0, 0, 255));
  list->AddRect(lo, hi, IM_COL32(255, 230, 0, 255));
}

}  // namespace lueur
