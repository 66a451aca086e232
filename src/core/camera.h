// Pinhole camera: eye, target, up and vertical field of view, turned into primary rays with sub-pixel jitter.
// Depends on core only.
#pragma once

#include "core/camera_spec.h"
#include "core/ray.h"

namespace lueur {

/// The share of the view's width or height that a framed box fills along its limiting axis (a margin of 4% each
/// side), as Blender's View All frames the model: tight, with a little air.
inline constexpr float kFramedShare = 0.92f;

/// How far from the box's centre an eye looking along `forward` (unit; `up` the view's unit up) must stand for the
/// projection of every corner of the box to fit kFramedShare of the view, whose half-angles have tangents
/// `tan_half_x` and `tan_half_y`: the nearest such eye, so that the box fills the view along its limiting axis.
float framing_distance(const Box3& box, const Vec3& forward, const Vec3& up, float tan_half_x, float tan_half_y);

/// A camera looking at the bounding box from its +z side (up +y), as close as framing_distance allows.
CameraSpec frame_box(const Box3& box, float fovy_degrees = 45.0f, float aspect = 1.0f);

/// The ready-to-trace form: an orthonormal basis and the image-plane scale.
struct Camera {
  Vec3 eye;
  Vec3 forward, right, up;  ///< right x up = -forward; +x of the image goes along `right`
  float tan_half_fovy = 1.0f;
  float aspect = 1.0f;
  int width = 1, height = 1;
};

/// Builds the basis; a degenerate spec (eye on target, up parallel to the view) gets a safe fallback up vector.
Camera make_camera(const CameraSpec& spec, int width, int height);

/// The ray through image position (x, y) in pixels, (0, 0) the top-left corner of the image, y pointing down.
/// The direction is normalised, so hit distances are world distances.
Ray camera_ray(const Camera& camera, float x, float y);

/// The inverse: the pixel position of a world point and whether it lies in front of the camera and inside the image.
bool project_to_pixel(const Camera& camera, const Vec3& point, float& x, float& y);

}  // namespace lueur
