// Pinhole camera maths.
#include "core/camera.h"

namespace lueur {

CameraSpec frame_box(const Box3& box, float fovy_degrees, float aspect) {
  CameraSpec spec;
  spec.fovy_degrees = fovy_degrees;
  const Vec3 centre = box.empty() ? Vec3(0.0f) : box.center();
  const float radius = std::max(0.5f * box.diagonal(), 1e-3f);
  const float half = glm::radians(fovy_degrees) * 0.5f;
  // The bounding sphere must fit the narrower of the two fields of view.
  const float tan_half = std::tan(half) * std::min(1.0f, aspect);
  const float distance = radius / std::sin(std::atan(tan_half)) * 1.05f;
  spec.target = centre;
  spec.eye = centre + Vec3(0.0f, 0.0f, distance);
  spec.up = Vec3(0.0f, 1.0f, 0.0f);
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
