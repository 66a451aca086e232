// How the window's mouse and keys move the camera: orbit around the target, pan in the view plane, dolly towards
// the target, fly with WASD/QE. Pure functions of a CameraSpec (no ImGui, no GLFW), so they are tested without one.
#pragma once

#include "core/camera.h"

namespace lueur {

/// Turns the camera around its target: `yaw` about the up vector, `pitch` about the camera's right axis
/// (radians; positive yaw turns the view to the right). Pitch stops short of the poles so up stays meaningful.
CameraSpec orbit(const CameraSpec& camera, float yaw, float pitch);

/// Moves eye and target together in the view plane by a fraction of the view's height at the target
/// (dx, dy in [-1, 1] per window height: dragging by the full height moves the scene by its visible height).
CameraSpec pan(const CameraSpec& camera, float dx, float dy);

/// Moves the eye towards the target by the factor 0.85^steps of its distance (negative steps move away).
CameraSpec dolly(const CameraSpec& camera, float steps);

/// Moves eye and target together: `forward`, `right`, `up` in world units along the camera's axes.
CameraSpec fly(const CameraSpec& camera, float forward, float right, float up);

}  // namespace lueur

namespace lueur {

/// Keeps the view direction and field of view, and moves so that the box fills the view along its limiting axis
/// with a small margin (core/camera.h: framing_distance), as Blender's View All does (F in the window).
CameraSpec frame_bounds(const CameraSpec& camera, const Box3& box, float aspect);

}  // namespace lueur
