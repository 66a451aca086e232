// The camera's specular path (see camera_path.h).
#include "integrator/camera_path.h"

#include "integrator/specular.h"

namespace lueur {

Ray leaving_ray(const Vec3& position, const Vec3& geometric_normal, const Vec3& dir) {
  Ray r;
  r.origin = offset_origin(position, geometric_normal, dir);
  r.dir = dir;
  return r;
}

CameraPath follow_camera_path(const TracedScene& traced, const Ray& ray, int max_bounces, PixelSampler& sampler,
                              uint64_t sample, uint32_t first_dimension, uint64_t& rays) {
  const Scene& scene = traced.scene;
  CameraPath path;
  path.ray = ray;
  for (;;) {
    path.hit = intersect_closest(traced.accel, path.ray);
    if (path.bounces > 0) ++rays;  // the first ray is the caller's, counted there
    if (!path.hit.found()) return path;
    const Material& material = scene.material_of(path.hit.triangle);
    const bool front = seen_from_front(scene, path.hit.triangle, path.ray.dir);
    if (front && material.emissive()) path.emission += path.throughput * material.ke;
    if (!material.is_specular()) return path;
    const SurfacePoint sp = make_surface_point(scene, path.ray, path.hit);
    sampler.start_sample(sample);
    const float u = sampler.get_2d_of_dimension(first_dimension + static_cast<uint32_t>(path.bounces)).x;
    const SpecularSample s =
        sample_specular(material, sp.albedo, sp.shading_normal, sp.geometric_normal, sp.wo, sp.front_face, u);
    path.through_specular = true;
    if (s.lobe == SpecularLobe::kBase) {
      // p is this surface, its Lambert base alone (brdf.h), weighted by 1 / the base's probability.
      path.throughput *= s.weight;
      return path;
    }
    if (s.lobe == SpecularLobe::kNone || path.bounces + 1 > max_bounces) {
      path.hit = Hit{};
      return path;
    }
    path.throughput *= s.weight;
    ++path.bounces;
    path.ray = leaving_ray(sp.position, sp.geometric_normal, s.dir);
  }
}

}  // namespace lueur
