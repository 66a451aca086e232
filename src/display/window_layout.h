// How the window is shared between the panel and the image: the panel is a column on the left, the image fills the
// rest, so that no part of the render is hidden under the controls. Pure arithmetic, tested without a window.
#pragma once

#include "display/display_pipeline.h"

namespace lueur {

/// A rectangle in window coordinates (GLFW's and ImGui's: origin top-left, y down; not framebuffer pixels).
struct WindowRect {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;

  bool contains(double px, double py) const { return px >= x && py >= y && px < x + width && py < y + height; }
};

struct WindowLayout {
  WindowRect image;               ///< where the image is shown, in window coordinates
  PixelRect image_pixels;         ///< the same in framebuffer pixels (GL's origin, bottom-left): the render's size
  bool panel_over_image = false;  ///< the window is too narrow for both: the image fills it, the panel floats over it
};

/// The narrowest image (window coordinates) that is laid out beside the panel; a narrower window shows the image
/// under the panel instead, so that a small window still shows a usable picture.
inline constexpr double kMinImageBesidePanel = 160.0;

/// Lays out a window of `window_width` x `window_height` (window coordinates) whose framebuffer is
/// `framebuffer_width` x `framebuffer_height` pixels (larger on a high-DPI screen), with a panel `panel_width` wide
/// on its left (0: no panel shown).
WindowLayout lay_out_window(int window_width, int window_height, int framebuffer_width, int framebuffer_height,
                            double panel_width);

/// The window's width (window coordinates) that shows an image `image_width` wide beside a panel `panel_width` wide.
int window_width_for_image(int image_width, double panel_width);

}  // namespace lueur
