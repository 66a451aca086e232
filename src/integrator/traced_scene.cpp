// Preparing a scene for tracing, and the shading frame at a hit.
#include "integrator/traced_scene.h"

namespace lueur {

std::shared_ptr<const TracedScene> prepare_scene(Scene scene, AccelKind accel) {
  auto traced = std::make_shared<TracedScene>();
  std::vector<Vec3> corners;
  corners.reserve(scene.triangles.size() * 3);
  for (const Triangle& t : scene.triangles)
    for (const uint32_t v : t.v) corners.push_back(scene.positions[v]);
  traced->lights = build_light_table(scene);
  const Box3 box = scene.bounds();
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
  traced->accel = build_accelerator(corners, accel, holes);
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
