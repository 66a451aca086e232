// Pinhole camera maths.
#include "core/camera.h"

#include <algorithm>
#include <cmath>

namespace lueur {

float framing_distance(const Box3& box, const Vec3& forward, const Vec3& up, float tan_half_x, float tan_half_y) {
  const Vec3 centre = box.empty() ? Vec3(0.0f) : box.center();
  const Vec3 right = glm::normalize(glm::cross(forward, up));
  const Vec3 true_up = glm::cross(right, forward);
  const float size = box.empty() ? 0.0f : box.diagonal();
  // A corner at (x, y) across the view and z towards the eye, seen from distance d, projects to x / (d - z): it fits
  // when d >= z + |x| / (share tan_half_x), and likewise for y. The farthest of these over the corners frames them
  // all; the eye also stays in front of every corner.
  float distance = 1e-3f;
  for (int corner = 0; corner < 8 && !box.empty(); ++corner) {
    const Vec3 p = Vec3((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                        (corner & 4) ? box.hi.z : box.lo.z) -
                   centre;
    const float x = std::abs(glm::dot(p, right)), y = std::abs(glm::dot(p, true_up)), z = -glm::dot(p, forward);
    distance = std::max({distance, z + x / (kFramedShare * tan_half_x), z + y / (kFramedShare * tan_half_y),
                         z + 1e-3f * size});
  }
  return distance;
}

CameraSpec frame_box(const Box3& box, float fovy_degrees, float aspect) {
  CameraSpec spec;
  spec.fovy_degrees = fovy_degrees;
  const float tan_half_y = std::tan(glm::radians(std::clamp(fovy_degrees, 0.01f, 179.0f)) * 0.5f);
  const Vec3 forward(0.0f, 0.0f, -1.0f), up(0.0f, 1.0f, 0.0f);
  const float distance = framing_distance(box, forward, up, tan_half_y * std::max(aspect, 1e-3f), tan_half_y);
  spec.target = box.empty() ? Vec3(0.0f) : box.center();
  spec.eye = spec.target - distance * forward;
  spec.up = up;
  return spec;
}

Camera make_camera(const CameraSpec& spec, int width, int height) {
  Camera c;
  c.eye = spec.eye;
  c.width = std::max(width, 1);
  c.height = std::max(height, 1);
  c.aspect = static_cast<float>(c.width) / static_cast<float>(c.height);
  c.tan_half_fovy = std::tan(glm::radians(std::clamp(spec.fovy_degrees, 0.01f, 179.0f)) * 0.5f);

  Vec3 forward = spec.target - spec.eye;
  if (!(glm::length(forward) > 0.0f) || !is_finite(forward)) forward = Vec3(0.0f, 0.0f, -1.0f);
  c.forward = glm::normalize(forward);
  Vec3 right = glm::cross(c.forward, spec.up);
  if (glm::length(right) < 1e-6f || !is_finite(right)) {
    // Up is parallel to the view: pick any perpendicular.
    right = glm::cross(c.forward, std::fabs(c.forward.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0));
  }
  c.right = glm::normalize(right);
  c.up = glm::cross(c.right, c.forward);
  return c;
}

Ray camera_ray(const Camera& c, float x, float y) {
  const float sx = (2.0f * x / static_cast<float>(c.width) - 1.0f) * c.tan_half_fovy * c.aspect;
  const float sy = (1.0f - 2.0f * y / static_cast<float>(c.height)) * c.tan_half_fovy;
  Ray ray;
  ray.origin = c.eye;
  ray.dir = glm::normalize(c.forward + sx * c.right + sy * c.up);
  return ray;
}

bool project_to_pixel(const Camera& c, const Vec3& point, float& x, float& y) {
  const Vec3 d = point - c.eye;
  const float depth = glm::dot(d, c.forward);
  if (!(depth > 0.0f)) return false;
  // The image plane at unit depth spans tan x aspect across and tan up, that is height / (2 tan) pixels per unit
  // both ways: one division (L2's reuse test projects every bounce hit).
  const float pixels_per_unit = 0.5f * static_cast<float>(c.height) / (depth * c.tan_half_fovy);
  x = 0.5f * static_cast<float>(c.width) + glm::dot(d, c.right) * pixels_per_unit;
  y = 0.5f * static_cast<float>(c.height) - glm::dot(d, c.up) * pixels_per_unit;
  return x >= 0.0f && y >= 0.0f && x < static_cast<float>(c.width) && y < static_cast<float>(c.height);
}

}  // namespace lueur
