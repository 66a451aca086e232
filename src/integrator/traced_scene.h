// A scene made ready to trace: the scene itself, its acceleration structure and its light table, built once and
// then read-only. Depends on the scene, the accelerator and render settings.
#pragma once

#include <memory>

#include "accel/accelerator.h"
#include "lights/light_sampler.h"
#include "scene/scene.h"

namespace lueur {

struct TracedScene {
  Scene scene;
  Accelerator accel;
  LightTable lights;
  Box3 bounds;            ///< the model's bounding box (Scene::bounds), computed once: a pass over every triangle
  float diagonal = 1.0f;  ///< bounding-box diagonal, the scale for default radii
  Vec3 lower{0.0f};       ///< bounding-box corner of the smallest coordinates
};

/// Builds the acceleration structure of the chosen kind and the light table (the expensive step of opening a
/// scene). Throws AccelError for Embree in a build without it.
/// `progress` is told the share of the BVH's build done.
std::shared_ptr<const TracedScene> prepare_scene(Scene scene, AccelKind accel = AccelKind::kLueur,
                                                 const BuildProgress& progress = {});

/// The surface seen at a hit, with its normals turned towards the side the ray came from (two-sided shading).
struct SurfacePoint {
  Vec3 position;
  Vec3 geometric_normal;  ///< unit, on the side of `wo`
  Vec3 shading_normal;    ///< unit, on the same side as the geometric normal
  Vec3 wo;                ///< unit direction back along the incoming ray
  Vec3 albedo{0.0f};      ///< the diffuse albedo here: the material's Kd, or its colour map at the hit
  uint32_t triangle = kNoHit;
  bool front_face = true;  ///< the ray arrived on the side the triangle's winding faces (the emitting side)
};

SurfacePoint make_surface_point(const Scene& scene, const Ray& ray, const Hit& hit);

/// Where rays leaving `sp` into the side it is seen from start: offset_origin for any direction on its geometric
/// normal's side (L1's shadow rays, L2's bounce rays and AO's rays all share it).
inline Vec3 leaving_origin(const SurfacePoint& sp) {
  return offset_origin(sp.position, sp.geometric_normal, sp.geometric_normal);
}

/// Whether a ray along `dir` meets triangle `tri` on the side its winding faces (the side an emitter shines on).
inline bool seen_from_front(const Scene& scene, uint32_t tri, const Vec3& dir) {
  return glm::dot(scene.geometric_normal_raw(tri), dir) < 0.0f;
}

}  // namespace lueur
