// Screenshots through the real display path without a window: the film goes through the display shaders into an
// off-screen framebuffer of an EGL or OSMesa context, optionally with the panel drawn on top, and is read back.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "display/display_pipeline.h"
#include "display/headless_context.h"
#include "ui/panel.h"

namespace lueur {

struct Screenshot {
  std::vector<uint8_t> rgb;  ///< rows top to bottom
  int width = 0, height = 0;
  std::string context;  ///< which context and renderer drew it, for the log
};

/// Renders `film` as the display would show it with these settings. `panel`, when given, is drawn over it as in the
/// window. Throws std::runtime_error when no context can be made or GL fails.
/// With `right`, an A/B split view: `film` left of the divider, `right` (rendered with compared_settings(shown))
/// right of it.
Screenshot render_headless_screenshot(HeadlessGl kind, const Film& film, const Settings& shown,
                                      PanelModel* panel = nullptr, const Film* right = nullptr);

}  // namespace lueur
