#include "display/window_layout.h"

#include <algorithm>
#include <cmath>

namespace lueur {

WindowLayout lay_out_window(int window_width, int window_height, int framebuffer_width, int framebuffer_height,
                            double panel_width) {
  WindowLayout layout;
  const double width = std::max(window_width, 0), height = std::max(window_height, 0);
  const int fb_width = std::max(framebuffer_width, 0), fb_height = std::max(framebuffer_height, 0);
  double panel = std::max(panel_width, 0.0);
  if (panel > 0.0 && width - panel < kMinImageBesidePanel) {
    layout.panel_over_image = true;
    panel = 0.0;
  }
  layout.image = WindowRect{panel, 0.0, width - panel, height};
  // The framebuffer may be scaled (high DPI); the panel's column is rounded to whole framebuffer pixels.
  const double scale = width > 0.0 ? fb_width / width : 1.0;
  const int panel_pixels = std::clamp(static_cast<int>(std::lround(panel * scale)), 0, fb_width);
  layout.image_pixels = PixelRect{panel_pixels, 0, fb_width - panel_pixels, fb_height};
  return layout;
}

int window_width_for_image(int image_width, double panel_width) {
  const int panel = static_cast<int>(std::lround(std::max(panel_width, 0.0)));
  // Too narrow for both, the panel floats over the image (lay_out_window), which then has the whole window.
  if (panel > 0 && image_width < kMinImageBesidePanel) return image_width;
  return image_width + panel;
}

}  // namespace lueur
