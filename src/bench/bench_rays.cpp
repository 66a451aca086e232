// Generating the benchmark's ray arrays with the renderer's own conventions (camera jitter, origin offsets,
// cosine sampling).
#include "bench/bench_rays.h"

#include "core/rng.h"
#include "core/sampling.h"
#include "integrator/direct_light.h"
#include "integrator/traced_scene.h"

namespace lueur::bench {

RaySets make_ray_sets(const BenchScene& b, const Accelerator& accel, int width, int height, uint64_t seed) {
  RaySets sets;
  const Scene& scene = b.scene;
  const Camera camera = make_camera(b.view, width, height);
  // Lights chosen uniformly by area through a running sum.
  std::vector<double> cdf;
  double total = 0.0;
  for (const uint32_t t : b.lights) cdf.push_back(total += scene.area(t));

  constexpr int kTile = 16;
  for (int ty = 0; ty < height; ty += kTile)
    for (int tx = 0; tx < width; tx += kTile)
      for (int y = ty; y < std::min(ty + kTile, height); ++y)
        for (int x = tx; x < std::min(tx + kTile, width); ++x) {
          const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x);
          Pcg32 rng = make_pixel_rng(seed, pixel, 0, RngPurpose::kCamera);
          const float jx = rng.next_float(), jy = rng.next_float();
          const Ray ray = camera_ray(camera, static_cast<float>(x) + jx, static_cast<float>(y) + jy);
          sets.primary.push_back(ray);
          const Hit hit = intersect_closest(accel, ray);
          if (!hit.found()) continue;
          const SurfacePoint sp = make_surface_point(scene, ray, hit);

          Vec3 wi = Frame::from_normal(sp.geometric_normal)
                        .to_world(sample_cosine_hemisphere(rng.next_float(), rng.next_float()));
          Ray bounce;
          bounce.origin = offset_origin(sp.position, sp.geometric_normal, wi);
          bounce.dir = wi;
          sets.bounce.push_back(bounce);

          if (cdf.empty() || !(total > 0.0)) continue;
          const double u = rng.next_float() * total;
          const size_t k =
              std::min(static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()), cdf.size() - 1);
          const Vec2 bary = sample_uniform_triangle(rng.next_float(), rng.next_float());
          const Vec3 target = scene.point(b.lights[k], bary.x, bary.y);
          wi = target - sp.position;
          if (!(glm::dot(wi, sp.geometric_normal) > 0.0f)) continue;  // the light is behind the surface
          Ray shadow;
          shadow.origin = offset_origin(sp.position, sp.geometric_normal, wi);
          shadow.dir = target - shadow.origin;
          shadow.tmax = kShadowReach;  // as the renderer
          sets.shadow.push_back(shadow);
        }
  return sets;
}

}  // namespace lueur::bench
