// The camera's path through mirrors and glass: a camera ray that meets a perfectly specular surface goes on,
// reflected or refracted (one branch, chosen by sampling), until it meets a surface that is not perfectly specular,
// an emitter seen from its back, or nothing. That surface is the pixel's p, where Le, L1, L2, AO and ln are
// estimated as for a surface seen directly, weighted by the path's throughput. Depends on the traced scene and the
// specular lobes.
#pragma once

#include <cstdint>

#include "core/pixel_sampler.h"
#include "integrator/traced_scene.h"

namespace lueur {

struct CameraPath {
  Ray ray;                     ///< the ray that reached p
  Hit hit;                     ///< p's hit; not found() where the path ended without one
  Vec3 throughput{1.0f};       ///< the product of the specular weights before p
  Vec3 emission{0.0f};         ///< Le: the emission met along the path (p's included), weighted
  int bounces = 0;             ///< scattering events before p (each a mirror or glass vertex, or a chosen base)
  bool through_specular = false;  ///< a mirror or glass was met first: p does not project to the pixel
};

/// Follows `ray` from the camera. Vertex j's lobe is chosen by dimension `first_dimension + j` of sample `sample`
/// of `sampler` (a fixed dimension per vertex, so that every choice of every pixel is the same whatever the thread);
/// more than `max_bounces` scattering events end the path. Counts the rays it traces in `rays`.
CameraPath follow_camera_path(const TracedScene& traced, const Ray& ray, int max_bounces, PixelSampler& sampler,
                              uint64_t sample, uint32_t first_dimension, uint64_t& rays);

/// The ray that leaves a surface point (position, unit geometric normal) along `dir`, from the side `dir` points to.
Ray leaving_ray(const Vec3& position, const Vec3& geometric_normal, const Vec3& dir);

}  // namespace lueur
