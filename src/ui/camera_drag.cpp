// Drags measured from their anchor, not frame by frame.
#include "ui/camera_drag.h"

#include "ui/camera_controls.h"

namespace lueur {

void begin_drag(CameraDrag& drag, DragMode mode, const CameraSpec& current, double press_x, double press_y) {
  drag.mode = mode;
  drag.anchor_x = press_x;
  drag.anchor_y = press_y;
  drag.base = current;
  drag.last = current;
}

CameraSpec continue_drag(CameraDrag& drag, DragMode mode, const CameraSpec& current, double x, double y,
                         double image_height) {
  if (drag.mode == DragMode::kNone || mode == DragMode::kNone || image_height <= 0.0) return current;
  if (mode != drag.mode || !(current == drag.last)) begin_drag(drag, mode, current, x, y);
  const auto h = static_cast<float>(image_height);
  const auto dx = static_cast<float>(x - drag.anchor_x) / h, dy = static_cast<float>(y - drag.anchor_y) / h;
  drag.last = mode == DragMode::kOrbit ? orbit(drag.base, kOrbitRadiansPerHeight * dx, -kOrbitRadiansPerHeight * dy)
                                       : pan(drag.base, dx, dy);
  return drag.last;
}

}  // namespace lueur
