// Camera moves in the camera's own basis.
#include "ui/camera_controls.h"

#include <algorithm>
#include <cmath>

namespace lueur {
namespace {

constexpr float kMaxPitchCosine = 0.995f;  // the eye stays about 5.7 degrees from the poles

struct Basis {
  Vec3 forward, right, up;
};

Basis basis_of(const CameraSpec& c) {
  const Camera camera = make_camera(c, 1, 1);
  return {camera.forward, camera.right, camera.up};
}

Vec3 rotate(const Vec3& v, const Vec3& axis, float angle) {
  // Rodrigues' formula.
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0f - c);
}

}  // namespace

CameraSpec orbit(const CameraSpec& camera, float yaw, float pitch) {
  const Vec3 world_up = glm::normalize(camera.up);
  Vec3 offset = camera.eye - camera.target;
  const float distance = glm::length(offset);
  if (distance <= 0.0f) return camera;
  // Yaw about the world up (turning the view right moves the eye left around the target).
  offset = rotate(offset, world_up, -yaw);
  // Pitch about the camera's right axis (a positive pitch lowers the eye), the eye's elevation clamped short of the
  // poles: a drag past a pole stops there, and dragging back turns the view back from there.
  const Vec3 right = glm::normalize(glm::cross(-offset, world_up));
  const float limit = std::asin(kMaxPitchCosine);
  const float elevation = std::asin(std::clamp(glm::dot(offset / distance, world_up), -1.0f, 1.0f));
  const float clamped = std::clamp(elevation - pitch, -limit, std::max(-limit, limit));
  if (clamped != elevation) offset = rotate(offset, right, elevation - clamped);
  CameraSpec out = camera;
  out.eye = camera.target + offset;
  return out;
}

CameraSpec pan(const CameraSpec& camera, float dx, float dy) {
  const Basis b = basis_of(camera);
  const float distance = glm::length(camera.target - camera.eye);
  const float visible_height = 2.0f * distance * std::tan(0.5f * camera.fovy_degrees * kPi / 180.0f);
  const Vec3 move = (-dx * b.right + dy * b.up) * visible_height;
  CameraSpec out = camera;
  out.eye += move;
  out.target += move;
  return out;
}

CameraSpec dolly(const CameraSpec& camera, float steps) {
  const Vec3 offset = camera.eye - camera.target;
  const float scale = std::pow(0.85f, steps);
  CameraSpec out = camera;
  // Never onto the target itself: the view direction would vanish.
  out.eye = camera.target + offset * std::max(scale, 1e-4f);
  return out;
}

CameraSpec fly(const CameraSpec& camera, float forward, float right, float up) {
  const Basis b = basis_of(camera);
  const Vec3 move = forward * b.forward + right * b.right + up * b.up;
  CameraSpec out = camera;
  out.eye += move;
  out.target += move;
  return out;
}

}  // namespace lueur

namespace lueur {

CameraSpec frame_bounds(const CameraSpec& camera, const Box3& box, float aspect) {
  if (box.empty()) return camera;
  const Basis b = basis_of(camera);
  const float tan_half_y = std::tan(0.5f * std::clamp(camera.fovy_degrees, 0.01f, 179.0f) * kPi / 180.0f);
  CameraSpec out = camera;
  out.target = box.center();
  out.eye = out.target - b.forward * framing_distance(box, b.forward, b.up, tan_half_y * std::max(aspect, 1e-3f),
                                                      tan_half_y);
  return out;
}

}  // namespace lueur
