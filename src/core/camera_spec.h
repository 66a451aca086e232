// How a view is specified: eye, target, up vector and vertical field of view. Plain data shared by the scenes
// (their default views), the settings and the camera the renderer builds from it. Depends on core/math.h only.
#pragma once

#include "core/math.h"

namespace lueur {

struct CameraSpec {
  Vec3 eye{0.0f, 0.0f, 1.0f};
  Vec3 target{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovy_degrees = 45.0f;
  bool operator==(const CameraSpec&) const = default;
};

}  // namespace lueur
