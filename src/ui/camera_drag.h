// A drag in the image turns or pans the camera by the cursor's distance from where the button went down: the same
// move however fast the mouse goes and however slowly frames come, and nothing of what the cursor did before the
// press. Pure functions of a CameraSpec and cursor positions (no GLFW, no ImGui), tested without a window.
#pragma once

#include "core/camera.h"

namespace lueur {

enum class DragMode { kNone, kOrbit, kPan };

/// Orbit: 3 radians per image height of cursor travel; pan: the scene follows the cursor (ui/camera_controls.h).
inline constexpr float kOrbitRadiansPerHeight = 3.0f;

struct CameraDrag {
  DragMode mode = DragMode::kNone;
  double anchor_x = 0.0, anchor_y = 0.0;  ///< where the cursor was when `base` was the camera
  CameraSpec base;                        ///< the camera at the anchor
  CameraSpec last;                        ///< the camera the drag last gave
};

/// Starts a drag from the camera `current` with the cursor at the press, (press_x, press_y).
void begin_drag(CameraDrag& drag, DragMode mode, const CameraSpec& current, double press_x, double press_y);

/// The camera for the cursor at (x, y) in a drag over an image `image_height` pixels tall: the drag's base moved by
/// the cursor's travel from the anchor. A drag whose mode changed (Shift pressed or let go), or whose camera was
/// moved meanwhile by something else (the wheel, a key, the panel), goes on from `current` and the cursor as they are.
CameraSpec continue_drag(CameraDrag& drag, DragMode mode, const CameraSpec& current, double x, double y,
                         double image_height);

inline void end_drag(CameraDrag& drag) { drag.mode = DragMode::kNone; }

}  // namespace lueur
