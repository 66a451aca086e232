// Preparing a scene for tracing, and the shading frame at a hit.
#include "integrator/traced_scene.h"

#include <cstddef>

#include "core/memory_budget.h"

namespace lueur {

std::shared_ptr<const TracedScene> prepare_scene(Scene scene, AccelKind accel, const BuildProgress& progress) {
  auto traced = std::make_shared<TracedScene>();
  traced->lights = build_light_table(scene);
  const Box3 box = scene.bounds();
  traced->bounds = box;
  traced->diagonal = std::max(box.diagonal(), 1e-6f);
  traced->lower = scene.triangles.empty() ? Vec3(0.0f) : box.lo;
  traced->scene = std::move(scene);
  // The filter reads the scene where it now stays, for as long as the accelerator lives.
  HitFilter holes;
  if (traced->scene.has_cutouts()) {
    holes.accepts = [](const void* context, uint32_t id, float u, float v) {
      return !static_cast<const Scene*>(context)->cut_out(id, u, v);
    };
    holes.context = &traced->scene;
  }
  // The BVH reads the corners where the scene keeps them, rather than from a copy of its own.
  static_assert(offsetof(Triangle, v) == 0 && sizeof(Triangle) % sizeof(uint32_t) == 0);
  const Scene& kept = traced->scene;
  IndexedTriangles triangles;
  triangles.positions = kept.positions.data();
  triangles.indices = kept.triangles.empty() ? nullptr : kept.triangles.front().v;
  triangles.stride = sizeof(Triangle) / sizeof(uint32_t);
  triangles.count = kept.triangles.size();
  traced->accel = build_accelerator(triangles, accel, holes, progress);
  release_free_memory();
  return traced;
}

SurfacePoint make_surface_point(const Scene& scene, const Ray& ray, const Hit& hit) {
  SurfacePoint sp;
  sp.triangle = hit.triangle;
  sp.position = scene.point(hit.triangle, hit.u, hit.v);
  sp.albedo = scene.albedo(hit.triangle, hit.u, hit.v);
  sp.wo = -glm::normalize(ray.dir);
  Vec3 ng = glm::normalize(scene.geometric_normal_raw(hit.triangle));
  sp.front_face = glm::dot(ng, sp.wo) > 0.0f;
  if (!sp.front_face) ng = -ng;
  Vec3 ns = scene.shading_normal(hit.triangle, hit.u, hit.v);
  if (glm::dot(ns, ng) < 0.0f) ns = -ns;
  sp.geometric_normal = ng;
  sp.shading_normal = ns;
  return sp;
}

}  // namespace lueur
