// The head-light (see camera_light.h).
#include "integrator/camera_light.h"

#include <cmath>

namespace lueur {

EmitterRecord make_camera_light(const Camera& camera, float diagonal, float scale) {
  const float size = std::isfinite(diagonal) && diagonal > 0.0f ? diagonal : 1.0f;
  const float radius = 0.03f * size;
  const Vec3 centre = camera.eye - 0.02f * size * camera.forward;
  // Corners at 90, 330 and 210 degrees in the image plane: clockwise as the camera sees them, so that the geometric
  // normal is +forward (right x up = -forward).
  const float c = 0.5f * std::sqrt(3.0f) * radius, s = 0.5f * radius;
  EmitterRecord light;
  light.p0 = centre + radius * camera.up;
  light.p1 = centre + c * camera.right - s * camera.up;
  light.p2 = centre - c * camera.right - s * camera.up;
  const Vec3 n = glm::cross(light.p1 - light.p0, light.p2 - light.p0);
  light.area = 0.5f * glm::length(n);
  light.normal = n / (2.0f * light.area);
  // Half the diagonal ahead of the eye is that plus the 2% behind it away from the light.
  const float distance = 0.52f * size;
  light.ke = Vec3(kPi * distance * distance / light.area * scale);
  return light;
}

}  // namespace lueur
