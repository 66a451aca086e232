// Area-light sampling for L1. Each sample: choose an emitter (per strategy; kImportance weighs them at the point
// first), a uniform point on it, and weight Le f cos_p cos_l / d^2 by 1 / (pmf / area) if the shadow ray reaches
// it. Where the surface point is close to the emitter's plane for the emitter's size (an emitting face meeting a lit
// one at an edge), that weight has no bound, and the point on the emitter is placed by solid angle instead
// (core/spherical_triangle.h): weight Le f cos_p solid_angle / pmf.
#include "integrator/direct_light.h"

#include <algorithm>
#include <array>
#include <vector>

#include "core/sampling.h"
#include "core/spherical_triangle.h"
#include "integrator/brdf.h"

namespace lueur {
namespace {

/// Area sampling's weight, area cos_light / d^2, is at most area / height^2 for a point at `height` above the
/// emitter's plane. Where that bound passes this, the emitter is sampled by solid angle, whose weight is at most 2 pi.
/// Measured: with 4 the closed box's L1 was a third quieter than with 16, but the default scene's frames were 2-6%
/// slower (its walls' top band sampled the ceiling light by solid angle); with 16 they are as fast as with area
/// sampling alone.
constexpr float kMaxAreaWeight = 16.0f;

/// An emitter that fills at least about this solid angle (sr) from the point is sampled by solid angle too, with the
/// numbers warped toward the cosine at the surface: across a large emitter area sampling's weight (cos_light / d^2)
/// and the cosine at the surface both vary several-fold, and every such sample pays for it. Measured on the bunny
/// under the light rig's sky (triangles of about 1.4 sr): the image's error at equal time fell 3x (BENCHMARKS).
constexpr float kLargeSolidAngle = 0.25f;

/// The height of `p` above the plane of the emitter with unit normal `n` through `corner`, on the side it shines.
inline float height_above(float nx, float ny, float nz, float px, float py, float pz, const Vec3& corner) {
  return nx * (px - corner.x) + ny * (py - corner.y) + nz * (pz - corner.z);
}

/// The squared distance from (px, py, pz) to the centroid of the triangle with corners p0, p1, p2.
inline float centroid_distance2(float p0x, float p0y, float p0z, float p1x, float p1y, float p1z, float p2x, float p2y,
                                float p2z, float px, float py, float pz) {
  const float cx = (p0x + p1x + p2x) * (1.0f / 3.0f) - px, cy = (p0y + p1y + p2y) * (1.0f / 3.0f) - py,
              cz = (p0z + p1z + p2z) * (1.0f / 3.0f) - pz;
  return cx * cx + cy * cy + cz * cz;
}

/// Whether an emitter of `area` is sampled by solid angle from a point at `height` above its plane and `distance2`
/// from its centroid: close to its plane for its size, or filling a large solid angle (area x height / distance^3
/// estimates it). (Every test made, with no short circuit: it runs in the branch-free lanes of
/// PlacedLightSamples::place.)
inline bool by_solid_angle(float area, float height, float distance2) {
  const bool close = area > kMaxAreaWeight * height * height;
  const bool large = area * height > kLargeSolidAngle * distance2 * std::sqrt(distance2);
  return (height > 0.0f) & (close | large);
}

/// A point on emitter `light` whose direction from `origin` (the surface point's leaving origin) is uniform over the
/// triangle's solid angle. Returns cos_surface x solid_angle, or 0 where the point cannot light the surface; `point`
/// and `wi` receive the point and the unit direction to it. The triangle is seen from the leaving origin, not from
/// the surface point itself: a point that lies on an emitter, rounded to a hair in front of its plane, would see it
/// fill a hemisphere (area sampling all but never finds that light); the leaving origin stands on the side the
/// surface faces.
float place_by_solid_angle(const SurfacePoint& sp, const Vec3& origin, const EmitterRecord& light, float u1, float u2,
                           Vec3& point, Vec3& wi) {
  const SphericalTriangle seen = make_spherical_triangle(origin, light.p0, light.p1, light.p2);
  if (!(seen.solid_angle > 0.0)) return 0.0f;
  double w1 = u1, w2 = u2;
  const double density = warp_toward_cosine(seen, glm::dvec3(sp.shading_normal), w1, w2);
  const glm::dvec3 direction = sample_spherical_triangle(seen, w1, w2);
  const glm::dvec3 normal(light.normal), from(origin);
  const double along = glm::dot(normal, direction);
  if (!(along < 0.0)) return 0.0f;  // parallel to the plane, or toward its back
  const double distance = glm::dot(normal, glm::dvec3(light.p0) - from) / along;
  point = Vec3(from + distance * direction);
  wi = Vec3(direction);
  const float cos_surface = glm::dot(sp.shading_normal, wi);
  if (cos_surface <= 0.0f || glm::dot(sp.geometric_normal, wi) <= 0.0f) return 0.0f;
  return cos_surface * static_cast<float>(seen.solid_angle / density);
}

/// A batch of light samples in plain arrays: the emitter each one chose and its numbers, then, once placed, the
/// direction to its point and what the point sends if nothing is in the way: a uniform point on the emitter's area,
/// or, where the point is close to the emitter's plane or the emitter fills a large solid angle, a point placed by
/// solid angle. `place` places every lane without branches (the compiler places several per instruction); the
/// lanes see one surface point (`place<false>`: L1 at a pixel's hit) or each its own (`place<true>`, after
/// `set_point`: L1 recomputed at several bounce hits at once). A single sample (sample_emitter) is a batch of one:
/// one piece of code places every light sample Lueur takes.
struct PlacedLightSamples {
  using Lanes = std::array<float, kSampleBatch>;
  Lanes u1, u2;                                       // the point's numbers
  Lanes p0x, p0y, p0z, p1x, p1y, p1z, p2x, p2y, p2z;  // the chosen emitter's corners
  Lanes nx, ny, nz, area, pmf;                        // its normal, area and probability of being chosen
  std::array<uint32_t, kSampleBatch> light;
  Lanes wi_x, wi_y, wi_z;  // unit direction to the point
  Lanes to_x, to_y, to_z;  // from the shadow ray's origin to the point
  Lanes scale;             // cos_surface cos_light area / d^2, or 0 where the point cannot light the surface
  std::array<bool, kSampleBatch> by_solid_angle_;  // placed again by solid angle (place_close_ones)
  // Each lane's surface point, its normals and its shadow rays' origin (place<true> only).
  Lanes sp_x, sp_y, sp_z, sn_x, sn_y, sn_z, gn_x, gn_y, gn_z, o_x, o_y, o_z;
  std::array<const SurfacePoint*, kSampleBatch> point_of;

  void gather(size_t k, const EmitterRecord& record, const LightChoice& choice) {
    p0x[k] = record.p0.x, p0y[k] = record.p0.y, p0z[k] = record.p0.z;
    p1x[k] = record.p1.x, p1y[k] = record.p1.y, p1z[k] = record.p1.z;
    p2x[k] = record.p2.x, p2y[k] = record.p2.y, p2z[k] = record.p2.z;
    nx[k] = record.normal.x, ny[k] = record.normal.y, nz[k] = record.normal.z;
    area[k] = choice.pmf > 0.0f ? record.area : 0.0f;  // a light that cannot be chosen sends nothing
    pmf[k] = choice.pmf;
    light[k] = choice.index;
  }

  void set_point(size_t k, const SurfacePoint& sp, const Vec3& origin) {
    sp_x[k] = sp.position.x, sp_y[k] = sp.position.y, sp_z[k] = sp.position.z;
    sn_x[k] = sp.shading_normal.x, sn_y[k] = sp.shading_normal.y, sn_z[k] = sp.shading_normal.z;
    gn_x[k] = sp.geometric_normal.x, gn_y[k] = sp.geometric_normal.y, gn_z[k] = sp.geometric_normal.z;
    o_x[k] = origin.x, o_y[k] = origin.y, o_z[k] = origin.z;
    point_of[k] = &sp;
  }

  /// Lane k's shadow-ray origin: its own, or the one all lanes share.
  template <bool kPerLane>
  Vec3 origin_of(size_t k, const Vec3& shared) const {
    return kPerLane ? Vec3(o_x[k], o_y[k], o_z[k]) : shared;
  }

  template <bool kPerLane>
  void place(size_t count, const SurfacePoint& sp, const Vec3& shadow_origin) {
    for (size_t k = 0; k < count; ++k) {
      const float px = kPerLane ? sp_x[k] : sp.position.x, py = kPerLane ? sp_y[k] : sp.position.y,
                  pz = kPerLane ? sp_z[k] : sp.position.z;
      const float snx = kPerLane ? sn_x[k] : sp.shading_normal.x, sny = kPerLane ? sn_y[k] : sp.shading_normal.y,
                  snz = kPerLane ? sn_z[k] : sp.shading_normal.z;
      const float gnx = kPerLane ? gn_x[k] : sp.geometric_normal.x, gny = kPerLane ? gn_y[k] : sp.geometric_normal.y,
                  gnz = kPerLane ? gn_z[k] : sp.geometric_normal.z;
      const float ox = kPerLane ? o_x[k] : shadow_origin.x, oy = kPerLane ? o_y[k] : shadow_origin.y,
                  oz = kPerLane ? o_z[k] : shadow_origin.z;
      const float su = std::sqrt(u1[k]);
      const float bx = su * (1.0f - u2[k]), by = su * u2[k];
      const float b0 = 1.0f - bx - by;
      const float lx = b0 * p0x[k] + bx * p1x[k] + by * p2x[k];
      const float ly = b0 * p0y[k] + bx * p1y[k] + by * p2y[k];
      const float lz = b0 * p0z[k] + bx * p1z[k] + by * p2z[k];
      const float tx = lx - px, ty = ly - py, tz = lz - pz;
      const float distance2 = tx * tx + ty * ty + tz * tz;
      const float inv_distance = 1.0f / std::sqrt(distance2);
      const float wx = tx * inv_distance, wy = ty * inv_distance, wz = tz * inv_distance;
      const float cos_light = -(nx[k] * wx + ny[k] * wy + nz[k] * wz);
      const float cos_surface = snx * wx + sny * wy + snz * wz;
      const float cos_geometric = gnx * wx + gny * wy + gnz * wz;
      // Non-short-circuit tests, and the division made whatever the outcome: no branch in the loop.
      const bool lit = (distance2 > 0.0f) & (cos_light > 0.0f) & !(cos_surface <= 0.0f) & !(cos_geometric <= 0.0f);
      const float unoccluded_scale = cos_surface * cos_light * area[k] / distance2;
      wi_x[k] = wx, wi_y[k] = wy, wi_z[k] = wz;
      to_x[k] = lx - ox, to_y[k] = ly - oy, to_z[k] = lz - oz;
      scale[k] = lit ? unoccluded_scale : 0.0f;
      const float height = height_above(nx[k], ny[k], nz[k], ox, oy, oz, Vec3(p0x[k], p0y[k], p0z[k]));
      const float to_centroid2 =
          centroid_distance2(p0x[k], p0y[k], p0z[k], p1x[k], p1y[k], p1z[k], p2x[k], p2y[k], p2z[k], ox, oy, oz);
      by_solid_angle_[k] = by_solid_angle(area[k], height, to_centroid2);
    }
  }

  /// Places again, by solid angle, the samples whose emitter is too close to the surface point for area sampling:
  /// few, one at a time. `records[light[k]]` is lane k's emitter.
  template <bool kPerLane>
  void place_close_ones(size_t count, const SurfacePoint& sp, const Vec3& shadow_origin, const EmitterRecord* records) {
    for (size_t k = 0; k < count; ++k) {
      if (!by_solid_angle_[k]) continue;
      const SurfacePoint& at = kPerLane ? *point_of[k] : sp;
      const Vec3 origin = origin_of<kPerLane>(k, shadow_origin);
      Vec3 point(0.0f), wi(0.0f);
      scale[k] = place_by_solid_angle(at, origin, records[light[k]], u1[k], u2[k], point, wi);
      wi_x[k] = wi.x, wi_y[k] = wi.y, wi_z[k] = wi.z;
      to_x[k] = point.x - origin.x, to_y[k] = point.y - origin.y, to_z[k] = point.z - origin.z;
    }
  }
};

/// One surface point's sums over its light samples: the reflected light, its part from the BRDF's diffuse term,
/// and the light arriving.
struct L1Sums {
  Vec3 reflected{0.0f}, diffuse{0.0f}, arriving{0.0f};

  void add(const Vec3& light, const Vec3& wi, const Material& material, const SurfacePoint& sp,
           const DirectLightOptions& options, const Vec3& f_diffuse) {
    if (light.r <= 0.0f && light.g <= 0.0f && light.b <= 0.0f) return;
    Vec3 f = eval_brdf(material, sp.albedo, sp.shading_normal, wi, sp.wo, options.blinn_k);
    if (options.specular_only) f -= f_diffuse;
    reflected += light * f;
    diffuse += light * f_diffuse;
    arriving += light;
  }
};

/// The emitters chosen for surface point `sp` by lanes [first, first + count) of `placed`, whose light-choice numbers
/// are `choice_u[first, first + count)`, gathered.
void choose_lights(const LightTable& table, LightStrategy strategy, const SurfacePoint& sp, const float* choice_u,
                   size_t first, size_t count, PlacedLightSamples& placed) {
  if (strategy == LightStrategy::kImportance) {
    LightWeights weights;
    weigh_light_clusters(table.clusters, sp.position, sp.shading_normal, weights);
    if (!weights.overflowed) {
      for (size_t k = first; k < first + count; ++k) {
        const LightChoice choice = choose_weighted_light(table.clusters, weights, choice_u[k]);
        placed.gather(k, table.records[choice.index], choice);
      }
      return;
    }
    // Overflowed: choose_light below chooses by power for kImportance.
  }
  for (size_t k = first; k < first + count; ++k) {
    const LightChoice choice = choose_light(table, strategy, choice_u[k]);
    placed.gather(k, table.records[choice.index], choice);
  }
}

/// Whether lane k of a placed batch can carry light and its shadow ray reaches the point; if so, `light` and `wi`
/// receive the light it brings (Le x scale / pmf) and the direction it arrives from.
template <bool kPerLane>
bool light_of_lane(const TracedScene& traced, const PlacedLightSamples& placed, size_t k, const Vec3& shadow_origin,
                   uint64_t& rays_traced, Vec3& light, Vec3& wi) {
  if (!(placed.scale[k] > 0.0f)) return false;
  if (!light_reaches(traced, placed.origin_of<kPerLane>(k, shadow_origin),
                     Vec3(placed.to_x[k], placed.to_y[k], placed.to_z[k]), rays_traced))
    return false;
  light = traced.lights.records[placed.light[k]].ke * placed.scale[k] / placed.pmf[k];
  wi = Vec3(placed.wi_x[k], placed.wi_y[k], placed.wi_z[k]);
  return true;
}

/// Light arriving at the surface from one point on emitter `light` (u1, u2 place it): Le cos_p cos_l area / d^2 by
/// area, Le cos_p solid_angle by solid angle (divided by the pdf of the point, not by a pmf), zero where the point is
/// hidden or cannot light the surface. `wi` receives the direction to the point. A batch of one lane.
Vec3 sample_emitter(const TracedScene& traced, const SurfacePoint& sp, const EmitterRecord& light, float u1, float u2,
                    Vec3& wi, uint64_t& rays_traced) {
  PlacedLightSamples placed;
  placed.u1[0] = u1;
  placed.u2[0] = u2;
  placed.gather(0, light, LightChoice{0, 1.0f});
  const Vec3 shadow_origin = leaving_origin(sp);
  placed.place<false>(1, sp, shadow_origin);
  placed.place_close_ones<false>(1, sp, shadow_origin, &light);
  if (!(placed.scale[0] > 0.0f) ||
      !light_reaches(traced, shadow_origin, Vec3(placed.to_x[0], placed.to_y[0], placed.to_z[0]), rays_traced))
    return Vec3(0.0f);
  wi = Vec3(placed.wi_x[0], placed.wi_y[0], placed.wi_z[0]);
  return light.ke * placed.scale[0];
}

/// Whether L1 at several points can share a batch's lanes: one shadow ray per sample to one chosen emitter, every
/// point's samples in one batch.
bool batches_points(const LightTable& table, const DirectLightOptions& options) {
  return !table.empty() && options.strategy != LightStrategy::kAll && !options.camera_light &&
         options.rays > 0 && options.rays <= kSampleBatch;
}

}  // namespace

bool light_reaches(const TracedScene& traced, const Vec3& origin, const Vec3& to_point, uint64_t& rays_traced) {
  Ray shadow;
  shadow.origin = origin;
  shadow.dir = to_point;
  shadow.tmin = 0.0f;
  shadow.tmax = kShadowReach;
  ++rays_traced;
  return !intersect_any(traced.accel, shadow);
}

Vec3 estimate_direct_light(const TracedScene& traced, const SurfacePoint& sp, const DirectLightOptions& options,
                           PixelSampler& sampler, uint64_t first_sample, uint64_t& rays_traced, Vec3* diffuse_part,
                           Vec3* arriving) {
  const LightTable& table = traced.lights;
  if (diffuse_part) *diffuse_part = Vec3(0.0f);
  if (arriving) *arriving = Vec3(0.0f);
  if ((table.empty() && !options.camera_light) || options.rays <= 0) return Vec3(0.0f);
  const Material& material = traced.scene.material_of(sp.triangle);
  if (!reflects_light(material)) return Vec3(0.0f);
  const Vec3 f_diffuse = eval_brdf_diffuse(material, sp.albedo, options.blinn_k);

  L1Sums sums;
  Vec3 wi(0.0f);
  if (table.empty()) {
    // Only the head-light below.
  } else if (options.strategy == LightStrategy::kAll) {
    for (int s = 0; s < options.rays; ++s) {
      sampler.start_sample(first_sample + static_cast<uint64_t>(s));
      for (uint32_t i = 0; i < table.size(); ++i) {
        const Vec2 u = sampler.get_2d();
        const Vec3 light = sample_emitter(traced, sp, table.records[i], u.x, u.y, wi, rays_traced);
        sums.add(light, wi, material, sp, options, f_diffuse);
      }
    }
  } else {
    // A batch of samples at a time: their numbers, then every light point placed (with no branch, so that the
    // compiler places several per instruction), then the shadow rays of the samples that can carry light.
    PlacedLightSamples placed;
    const Vec3 shadow_origin = leaving_origin(sp);
    for (int batch = 0; batch < options.rays; batch += kSampleBatch) {
      const auto count = static_cast<size_t>(std::min(kSampleBatch, options.rays - batch));
      std::array<float, kSampleBatch> choice_u;
      sampler.draw_1d_2d(first_sample + static_cast<uint64_t>(batch), static_cast<int>(count), choice_u.data(),
                         placed.u1.data(), placed.u2.data());
      choose_lights(table, options.strategy, sp, choice_u.data(), 0, count, placed);
      placed.place<false>(count, sp, shadow_origin);
      placed.place_close_ones<false>(count, sp, shadow_origin, table.records.data());
      for (size_t k = 0; k < count; ++k) {
        Vec3 light(0.0f);
        if (light_of_lane<false>(traced, placed, k, shadow_origin, rays_traced, light, wi))
          sums.add(light, wi, material, sp, options, f_diffuse);
      }
    }
  }
  if (options.camera_light) {
    // One point on the head-light per sample, from the dimension after those the scene's lights drew: with it off,
    // every other number stays as it was.
    const auto dimension =
        static_cast<uint32_t>(table.empty() ? 0 : (options.strategy == LightStrategy::kAll ? table.size() : 2));
    for (int s = 0; s < options.rays; ++s) {
      sampler.start_sample(first_sample + static_cast<uint64_t>(s));
      const Vec2 u = sampler.get_2d_of_dimension(dimension);
      const Vec3 light = sample_emitter(traced, sp, *options.camera_light, u.x, u.y, wi, rays_traced);
      sums.add(light, wi, material, sp, options, f_diffuse);
    }
  }
  const float inv = 1.0f / static_cast<float>(options.rays);
  if (diffuse_part) *diffuse_part = sums.diffuse * inv;
  if (arriving) *arriving = sums.arriving * inv;
  return sums.reflected * inv;
}

void estimate_direct_light_at_points(const TracedScene& traced, const SurfacePoint* const* points,
                                     const uint64_t* first_samples, size_t count, const DirectLightOptions& options,
                                     PixelSampler& sampler, uint64_t& rays_traced, Vec3* l1, Vec3* arriving) {
  const LightTable& table = traced.lights;
  if (!batches_points(table, options)) {
    for (size_t i = 0; i < count; ++i)
      l1[i] = estimate_direct_light(traced, *points[i], options, sampler, first_samples[i], rays_traced, nullptr,
                                    arriving ? &arriving[i] : nullptr);
    return;
  }
  const auto rays = static_cast<size_t>(options.rays);
  const size_t points_per_batch = static_cast<size_t>(kSampleBatch) / rays;
  const float inv = 1.0f / static_cast<float>(options.rays);
  PlacedLightSamples placed;
  std::array<size_t, kSampleBatch> batch_points;  // which of `points` each run of `rays` lanes serves
  std::array<uint64_t, kSampleBatch> batch_first_samples;
  std::array<float, kSampleBatch> choice_u;
  size_t next = 0;
  while (next < count) {
    // The next points that reflect light take a run of lanes each; the others have no L1.
    size_t in_batch = 0;
    for (; next < count && in_batch < points_per_batch; ++next) {
      l1[next] = Vec3(0.0f);
      if (arriving) arriving[next] = Vec3(0.0f);
      const SurfacePoint& sp = *points[next];
      if (!reflects_light(traced.scene.material_of(sp.triangle))) continue;
      const Vec3 origin = leaving_origin(sp);
      for (size_t k = in_batch * rays; k < (in_batch + 1) * rays; ++k) placed.set_point(k, sp, origin);
      batch_first_samples[in_batch] = first_samples[next];
      batch_points[in_batch++] = next;
    }
    const size_t lanes = in_batch * rays;
    sampler.draw_1d_2d_runs(batch_first_samples.data(), static_cast<int>(in_batch), options.rays, choice_u.data(),
                            placed.u1.data(), placed.u2.data());
    for (size_t j = 0; j < in_batch; ++j)
      choose_lights(table, options.strategy, *points[batch_points[j]], choice_u.data(), j * rays, rays, placed);
    placed.place<true>(lanes, *points[0], Vec3(0.0f));
    placed.place_close_ones<true>(lanes, *points[0], Vec3(0.0f), table.records.data());
    for (size_t j = 0; j < in_batch; ++j) {
      const size_t i = batch_points[j];
      const SurfacePoint& sp = *points[i];
      const Material& material = traced.scene.material_of(sp.triangle);
      const Vec3 f_diffuse = eval_brdf_diffuse(material, sp.albedo, options.blinn_k);
      L1Sums sums;
      for (size_t k = j * rays; k < (j + 1) * rays; ++k) {
        Vec3 light(0.0f), wi(0.0f);
        if (light_of_lane<true>(traced, placed, k, Vec3(0.0f), rays_traced, light, wi))
          sums.add(light, wi, material, sp, options, f_diffuse);
      }
      l1[i] = sums.reflected * inv;
      if (arriving) arriving[i] = sums.arriving * inv;
    }
  }
}

}  // namespace lueur
