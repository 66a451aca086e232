// The embedded default scene: the report's Cornell box with its two blocks and a low-poly apple on the short block,
// lit by the ceiling light (two large triangles) and a small wall lamp cut into many small triangles, so that the
// light-sampling strategies visibly differ. Depends on the scene layer only.
#pragma once

#include "core/camera_spec.h"
#include "scene/scene.h"

namespace lueur {

/// The Cornell box from the published measurements (millimetres; the camera looks along +z, +x is to its left),
/// without shading normals: smoothing is applied like for any loaded scene. Emitters are collected.
Scene make_default_scene();

/// The published Cornell box camera: eye (278, 273, -800) looking along +z, 39.3 degrees vertical field of view
/// (2 atan(12.5 / 35): a 25 mm film behind a 35 mm lens).
inline CameraSpec default_scene_camera() {
  return CameraSpec{Vec3(278.0f, 273.0f, -800.0f), Vec3(278.0f, 273.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), 39.3077f};
}

}  // namespace lueur
