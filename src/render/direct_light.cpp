// Area-light sampling for L1. Each sample: choose an emitter (per strategy), a uniform point on it, and weight
// Le f cos_p cos_l / d^2 by 1 / (pmf / area) if the shadow ray reaches it.
#include "render/direct_light.h"

#include <algorithm>
#include <array>

#include "core/sampling.h"
#include "render/brdf.h"

namespace lueur {
namespace {

/// Light arriving at the surface from one uniform point on emitter `table_index`: Le cos_p cos_l area / d^2
/// (divided by the area pdf, not by the pmf), zero when the point is hidden or faces away. `wi` receives the
/// direction to the point.
Vec3 sample_emitter(const TracedScene& traced, const SurfacePoint& sp, uint32_t table_index, float u1, float u2,
                    Vec3& wi, uint64_t& rays_traced) {
  const EmitterRecord& light = traced.lights.records[table_index];
  const Vec2 b = sample_uniform_triangle(u1, u2);
  const Vec3 light_point = (1.0f - b.x - b.y) * light.p0 + b.x * light.p1 + b.y * light.p2;

  const Vec3 to_light = light_point - sp.position;
  const float distance2 = glm::dot(to_light, to_light);
  if (!(distance2 > 0.0f)) return Vec3(0.0f);
  wi = to_light * (1.0f / std::sqrt(distance2));

  // Emitters shine on the side of their geometric normal only.
  const float cos_light = -glm::dot(light.normal, wi);
  if (!(cos_light > 0.0f)) return Vec3(0.0f);
  // Light must arrive on the side the surface is seen from, by both normals (no leaks through the surface).
  const float cos_surface = glm::dot(sp.shading_normal, wi);
  if (cos_surface <= 0.0f || glm::dot(sp.geometric_normal, wi) <= 0.0f) return Vec3(0.0f);

  Ray shadow;
  shadow.origin = offset_origin(sp.position, sp.geometric_normal, wi);
  shadow.dir = light_point - shadow.origin;
  shadow.tmin = 0.0f;
  shadow.tmax = 1.0f - 1e-4f;  // stop just short of the light itself
  ++rays_traced;
  if (intersect_any(traced.accel, shadow)) return Vec3(0.0f);
  return light.ke * (cos_surface * cos_light * light.area / distance2);
}

}  // namespace

Vec3 estimate_direct_light(const TracedScene& traced, const SurfacePoint& sp, const DirectLightOptions& options,
                           PixelSampler& sampler, uint64_t first_sample, uint64_t& rays_traced, Vec3* diffuse_part) {
  const LightTable& table = traced.lights;
  if (diffuse_part) *diffuse_part = Vec3(0.0f);
  if (table.empty() || options.rays <= 0) return Vec3(0.0f);
  const Material& material = traced.scene.material_of(sp.triangle);
  const Vec3 f_diffuse = eval_brdf_diffuse(material, options.blinn_k);

  Vec3 sum(0.0f), diffuse_sum(0.0f);
  auto accumulate = [&](const Vec3& arriving, const Vec3& wi) {
    if (arriving.r <= 0.0f && arriving.g <= 0.0f && arriving.b <= 0.0f) return;
    Vec3 f = eval_brdf(material, sp.shading_normal, wi, sp.wo, options.blinn_k);
    if (options.specular_only) f -= f_diffuse;
    sum += arriving * f;
    diffuse_sum += arriving * f_diffuse;
  };
  Vec3 wi(0.0f);
  if (options.strategy == LightStrategy::kAll) {
    for (int s = 0; s < options.rays; ++s) {
      sampler.start_sample(first_sample + static_cast<uint64_t>(s));
      for (uint32_t i = 0; i < table.size(); ++i) {
        const Vec2 u = sampler.get_2d();
        accumulate(sample_emitter(traced, sp, i, u.x, u.y, wi, rays_traced), wi);
      }
    }
  } else {
    // The numbers of a batch of samples first (computed together), then the samples one by one.
    std::array<float, kSampleBatch> choice_u, point_x, point_y;
    for (int batch = 0; batch < options.rays; batch += kSampleBatch) {
      const int count = std::min(kSampleBatch, options.rays - batch);
      sampler.draw_1d_2d(first_sample + static_cast<uint64_t>(batch), count, choice_u.data(), point_x.data(),
                         point_y.data());
      for (size_t k = 0; k < static_cast<size_t>(count); ++k) {
        const LightChoice choice = choose_light(table, options.strategy, choice_u[k]);
        if (choice.pmf > 0.0f)
          accumulate(sample_emitter(traced, sp, choice.index, point_x[k], point_y[k], wi, rays_traced) / choice.pmf,
                     wi);
      }
    }
  }
  const float inv = 1.0f / static_cast<float>(options.rays);
  if (diffuse_part) *diffuse_part = diffuse_sum * inv;
  return sum * inv;
}

}  // namespace lueur
