// L2 with screen-space reuse, and ambient occlusion.
#include "integrator/indirect_light.h"

#include <algorithm>
#include <array>

#include "core/sampling.h"
#include "integrator/brdf.h"
#include "integrator/camera_light.h"
#include "integrator/direct_light.h"

namespace lueur {
namespace {

/// How far, in pixel footprints on q's plane, a pixel's primary hit may lie from q and still count as q. Both lie
/// in the same pixel, so their distance is at most the pixel's diagonal (sqrt 2) in that measure.
constexpr float kReuseFootprints = 1.5f;

/// A bounce ray that hit q, waiting for its L1(q).
struct PendingBounce {
  Ray ray;
  Hit hit;
  Vec3 q_position{0.0f};
  uint64_t sample = 0;
  int pixel = -1;  ///< the screen pixel q projects to, or -1 (or no reuse, or not looked at yet)
  bool has_surface = false;
  SurfacePoint surface;  ///< q's full surface point, made when first needed (surface_of)
  L1CacheKey key;        ///< with the L1 store: q's jittered cell (key_for_store), whose slot is being loaded
  uint64_t hash = 0;
  Vec3 facing{0.0f};  ///< q's unit geometric normal on the side the ray came from (set with the key)
  bool fills_store = false;  ///< with the store, where no ready cell served q: an L1(q) traced anew becomes a record
};

/// q's full surface point, made once.
const SurfacePoint& surface_of(const Scene& scene, PendingBounce& b) {
  if (!b.has_surface) {
    b.surface = make_surface_point(scene, b.ray, b.hit);
    b.has_surface = true;
  }
  return b.surface;
}

/// Room for a batch of pending bounces, left unconstructed (each is written whole before it is read): constructing
/// sixteen of them per pixel and batch cost 1% of a frame.
struct PendingBatch {
  PendingBatch() {}
  union {
    std::array<PendingBounce, kSampleBatch> items;
  };
};

/// The screen pixel that q projects to, or -1 outside the image.
int screen_pixel_of(const Camera& camera, const ScreenBuffer& screen, const Vec3& q) {
  float x = 0.0f, y = 0.0f;
  if (!project_to_pixel(camera, q, x, y)) return -1;
  const int px = std::min(static_cast<int>(x), screen.width - 1), py = std::min(static_cast<int>(y), screen.height - 1);
  return py * screen.width + px;
}

/// Whether `pixel`'s primary ray hit q: the same triangle, within kReuseFootprints of q on its plane. `q_normal`
/// may have any length: it is normalised only once the triangle matches.
bool pixel_saw_q(const Camera& camera, const ScreenBuffer& screen, int pixel, uint32_t triangle, const Vec3& q,
                 const Vec3& q_normal) {
  const auto i = static_cast<size_t>(pixel);
  if (screen.triangle[i] != triangle) return false;
  // The pixel's footprint at q's depth, stretched by the obliquity of q's plane to the view ray:
  //   |seen - q| <= k footprint / obliquity, obliquity = max(|cos|, 0.05), cos = (to_q . n) / |to_q|,
  // squared and multiplied through by |to_q|^2, so that no square root or division is needed.
  const Vec3 to_q = q - camera.eye;
  const float distance2 = glm::dot(to_q, to_q);
  const float depth = glm::dot(to_q, camera.forward);
  const float tolerance = kReuseFootprints * 2.0f * camera.tan_half_fovy * depth / static_cast<float>(camera.height);
  const float along = glm::dot(to_q, glm::normalize(q_normal));
  const float obliquity2_distance2 = std::max(along * along, 0.05f * 0.05f * distance2);
  const Vec3 gap = screen.pixels[i].position - q;
  return glm::dot(gap, gap) * obliquity2_distance2 <= tolerance * tolerance * distance2;
}

}  // namespace

int find_reusable_pixel(const Camera& camera, const ScreenBuffer& screen, uint32_t triangle, const Vec3& q,
                        const Vec3& q_normal) {
  const int pixel = screen_pixel_of(camera, screen, q);
  return pixel >= 0 && pixel_saw_q(camera, screen, pixel, triangle, q, q_normal) ? pixel : -1;
}

namespace {

/// The rays of a batch of directions on the cosine-weighted hemisphere around a surface point's shading normal,
/// computed lane by lane and without branches, so that the compiler computes several per instruction. `open[k]` is
/// false where the direction dips below the geometric surface: such rays would leak through it and count as zero.
/// Every open ray leaves from the point's leaving_origin.
class BounceDirections {
 public:
  explicit BounceDirections(const SurfacePoint& sp)
      : shading_frame_(Frame::from_normal(sp.shading_normal)),
        geometric_normal_(sp.geometric_normal),
        origin_(leaving_origin(sp)) {}

  /// Samples `first_sample` onwards of `sampler`, `count` of them (at most kSampleBatch).
  void draw(PixelSampler& sampler, uint64_t first_sample, int count) {
    Lanes u1, u2;
    sampler.draw_2d(first_sample, count, u1.data(), u2.data());
    place(static_cast<size_t>(count), u1, u2);
  }
  bool open(size_t k) const { return open_[k]; }
  Ray ray(size_t k) const {
    Ray r;
    r.origin = origin_;
    r.dir = Vec3(x_[k], y_[k], z_[k]);
    return r;
  }

 private:
  using Lanes = std::array<float, kSampleBatch>;

  void place(size_t count, const Lanes& u1, const Lanes& u2) {
    const Vec3 &t = shading_frame_.tangent, &b = shading_frame_.bitangent, &n = shading_frame_.normal;
    const Vec3& g = geometric_normal_;
    for (size_t k = 0; k < count; ++k) {
      const Vec3 local = sample_cosine_hemisphere(u1[k], u2[k]);
      x_[k] = local.x * t.x + local.y * b.x + local.z * n.x;
      y_[k] = local.x * t.y + local.y * b.y + local.z * n.y;
      z_[k] = local.x * t.z + local.y * b.z + local.z * n.z;
      open_[k] = (local.z > 0.0f) & (x_[k] * g.x + y_[k] * g.y + z_[k] * g.z > 0.0f);
    }
  }

  Frame shading_frame_;
  Vec3 geometric_normal_, origin_;
  Lanes x_, y_, z_;
  std::array<bool, kSampleBatch> open_;
};

}  // namespace

void ScreenBuffer::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  triangle.assign(n, kNoHit);
  pixels.assign(n, ScreenPixel{});
  l1_average.clear();
}

namespace {

/// The part of L1(q) toward p that the BRDF has beyond its diffuse term, traced with `recompute`'s rays: what is
/// added where only the view-independent part of L1 was taken from the screen or the store.
Vec3 view_dependent_rest(const TracedScene& traced, const SurfacePoint& q, const DirectLightOptions& recompute,
                         PixelSampler& sampler, uint64_t first_shadow_sample, uint64_t& rays_traced) {
  DirectLightOptions rest = recompute;
  rest.specular_only = true;
  return estimate_direct_light(traced, q, rest, sampler, first_shadow_sample, rays_traced);
}

/// Sets `b`'s jittered cell, and starts loading the cell's slot. The key needs only q and the side of its triangle
/// that the ray came from, not the full surface point.
void key_for_store(const Scene& scene, const L1CacheAccess& cache, PendingBounce& b) {
  b.facing = glm::normalize(scene.geometric_normal_raw(b.hit.triangle));
  if (glm::dot(b.facing, b.ray.dir) > 0.0f) b.facing = -b.facing;
  const float u1 = cache.jitter->next_float(), u2 = cache.jitter->next_float();
  b.key = jittered_key(*cache.grid, b.q_position, b.facing, u1, u2);
  b.hash = hash_of(b.key);
  cache.store->prefetch(b.hash);
}

/// L1(q) toward p from the L1 store, where q's jittered cell is ready (returns true; otherwise false and nothing
/// traced): the BRDF's constant part times the cell's arriving light, plus whatever the BRDF has beyond it, traced
/// toward p.
bool l1_from_ready_cell(const TracedScene& traced, PendingBounce& b, const RenderSettings& settings,
                        const DirectLightOptions& recompute, const L1CacheAccess& cache, PixelSampler& sampler,
                        uint64_t first_shadow_sample, uint64_t& rays_traced, Vec3& l1_q) {
  const L1CacheCell* cell = nullptr;
  const StoreUse use = use_of_store(cache, b.key, b.hash, cell);
  if (use != StoreUse::kRead) {
    // A cell that is there grows; a missing one is made at the frame's end unless the store is full there.
    b.fills_store = use == StoreUse::kFeed;
    return false;
  }
  const Vec3 arriving = cell->sum / static_cast<float>(cell->samples);
  const Material& mq = traced.scene.material_of(b.hit.triangle);
  // brdf_is_constant reads q's shading normal (turned to the side the ray came from, as make_surface_point turns
  // it) only for the report's mix with a lobe of exponent 0: only then is it interpolated, not the whole surface point.
  Vec3 n = b.facing;
  if (!mq.has_specular() && settings.blinn_k < 1.0f && mq.ns == 0.0f) {
    n = traced.scene.shading_normal(b.hit.triangle, b.hit.u, b.hit.v);
    if (glm::dot(n, b.facing) < 0.0f) n = -n;
  }
  // The store holds the light arriving at q; q's own albedo (its colour map at q) turns it into L1.
  const Vec3 kd = traced.scene.albedo(b.hit.triangle, b.hit.u, b.hit.v);
  if (brdf_is_constant(mq, settings.blinn_k, n, -b.ray.dir)) {
    l1_q = constant_brdf(mq, kd, settings.blinn_k) * arriving;
  } else {
    l1_q =
        eval_brdf_diffuse(mq, kd, settings.blinn_k) * arriving +
        view_dependent_rest(traced, surface_of(traced.scene, b), recompute, sampler, first_shadow_sample, rays_traced);
  }
  return true;
}

/// Turns L1 at a point of albedo `seen` into L1 at a point of albedo `wanted`; false (nothing changed) where a
/// channel of `seen` is black and that of `wanted` is not, whose light the pixel cannot tell.
bool rescale_to_albedo(const Vec3& seen, const Vec3& wanted, Vec3& l1) {
  Vec3 scaled(0.0f);
  for (int c = 0; c < 3; ++c) {
    if (seen[c] > 0.0f)
      scaled[c] = l1[c] * (wanted[c] / seen[c]);
    else if (wanted[c] > 0.0f)
      return false;
  }
  l1 = scaled;
  return true;
}

/// What a bounce along `dir` brings to p, whose L1(q) is `l1_q`: f cos / pdf with pdf = cos / pi.
Vec3 bounce_contribution(const Material& material, const SurfacePoint& sp, const Vec3& dir, float blinn_k,
                         const Vec3& l1_q) {
  return eval_brdf(material, sp.albedo, sp.shading_normal, dir, sp.wo, blinn_k) * kPi * l1_q;
}

}  // namespace

IndirectResult estimate_indirect_light(const TracedScene& traced, const Camera& camera, const ScreenBuffer& screen,
                                       const SurfacePoint& sp, const RenderSettings& settings,
                                       PixelSampler& bounce_sampler, PixelSampler& recompute_sampler,
                                       uint64_t first_sample, uint64_t& rays_traced, const L1CacheAccess* cache,
                                       SharedBounce* shared, int shared_count) {
  IndirectResult result;
  if (settings.l2_rays <= 0) return result;
  const Scene& scene = traced.scene;
  const Material& material = scene.material_of(sp.triangle);
  if (!reflects_light(material)) return result;

  DirectLightOptions recompute;
  // `importance` weighs every emitter cluster at the point it shades: worth it for a pixel's 16 shadow rays, not for
  // the 2 of a recomputed L1(q), whose error L2's bounce directions outweigh. Measured on the default scene (256x256,
  // 24 frames): with power here the frame is 8% faster, and the image's error at equal time 2% lower.
  recompute.strategy = settings.lights == LightStrategy::kImportance ? LightStrategy::kPower : settings.lights;
  recompute.rays = settings.recompute_rays();
  recompute.blinn_k = settings.blinn_k;
  EmitterRecord head_light;
  if (settings.camera_light) {
    head_light = make_camera_light(camera, traced.diagonal);
    recompute.camera_light = &head_light;
  }

  // With the store, an L1(q) traced anew also fills q's cell, with kL1CacheFillRays rays (with the recompute share
  // where the store is full and would refuse the cell: there the fill would buy nothing). Each bounce's shadow rays
  // are its own run of the recompute sampler's samples, as long as the longest estimate a bounce hit may trace.
  DirectLightOptions fill = recompute;
  if (cache) fill.rays = kL1CacheFillRays;
  const int shadow_run = std::max(recompute.rays, fill.rays);

  BounceDirections directions(sp);
  const bool reuse = uses_screen(settings.reuse);
  for (int batch_start = 0; batch_start < settings.l2_rays; batch_start += kSampleBatch) {
    // Trace a batch of bounce rays first, starting the reads of the screen or the store as each ray lands: the next
    // ray's traversal then hides their cache misses, which otherwise cost more than the traversal itself.
    PendingBatch pending;
    int pending_count = 0;
    const int count = std::min(kSampleBatch, settings.l2_rays - batch_start);
    directions.draw(bounce_sampler, first_sample + static_cast<uint64_t>(batch_start), count);
    for (size_t k = 0; k < static_cast<size_t>(count); ++k) {
      const int index = batch_start + static_cast<int>(k);
      if (!directions.open(k)) {
        if (index < shared_count) shared[index].open = false;
        continue;
      }
      const Ray ray = directions.ray(k);
      ++rays_traced;
      ++result.bounce_rays;
      const Hit hit = intersect_closest(traced.accel, ray);
      if (index < shared_count) shared[index] = SharedBounce{true, ray, hit, false, {}, 0};
      if (!hit.found()) continue;
      // A black q (a light, the rig's sky) has L1(q) = 0: nothing to look up, trace or count among the bounce hits
      // that the screen, the store or a recomputation serve.
      if (!reflects_light(scene.material_of(hit.triangle))) continue;
      PendingBounce& b = pending.items[static_cast<size_t>(pending_count)];
      b.ray = ray;
      b.hit = hit;
      b.q_position = scene.point(hit.triangle, hit.u, hit.v);  // the reuse test and the key need only q and its plane
      b.sample = first_sample + static_cast<uint64_t>(batch_start) + k;
      b.has_surface = false;  // the rest is written only when set
      b.pixel = -1;
      b.fills_store = false;
      if (cache) {
        // The store is asked first (where it has a ready cell, its L1 has at least kL1CacheMinSamples samples, often far more, and the least bias);
        // the screen, if at all, only where it has not.
        key_for_store(scene, *cache, b);
        if (index < shared_count) {
          shared[index].keyed = true;
          shared[index].key = b.key;
          shared[index].hash = b.hash;
        }
      } else if (reuse) {
        b.pixel = screen_pixel_of(camera, screen, b.q_position);
        if (b.pixel >= 0) {
          __builtin_prefetch(&screen.triangle[static_cast<size_t>(b.pixel)]);
          __builtin_prefetch(&screen.pixels[static_cast<size_t>(b.pixel)]);
        }
      }
      ++pending_count;
    }

    // L1(q) toward p: from the store's ready cell, or from the screen where the camera saw q. The rest is traced
    // anew below, the whole batch's at once.
    std::array<size_t, kSampleBatch> traced_anew;
    size_t traced_anew_count = 0;
    for (size_t k = 0; k < static_cast<size_t>(pending_count); ++k) {
      PendingBounce& b = pending.items[k];
      ++result.bounce_hits;
      const uint64_t first_shadow_sample = first_sample_of_run(b.sample, shadow_run);
      Vec3 l1_q(0.0f);
      bool reused = false;
      const bool cached = cache && l1_from_ready_cell(traced, b, settings, recompute, *cache, recompute_sampler,
                                                      first_shadow_sample, rays_traced, l1_q);
      if (!cached && reuse) {
        if (cache) b.pixel = screen_pixel_of(camera, screen, b.q_position);
        if (b.pixel >= 0 && pixel_saw_q(camera, screen, b.pixel, b.hit.triangle, b.q_position,
                                        scene.geometric_normal_raw(b.hit.triangle))) {
          const auto i = static_cast<size_t>(b.pixel);
          l1_q = screen.reused_l1(i, settings.reuse);
          // On a colour map the pixel's texel need not be q's: L1 scales with the albedo, channel by channel.
          reused = scene.material_of(b.hit.triangle).diffuse_texture < 0 ||
                   rescale_to_albedo(screen.pixels[i].albedo, scene.albedo(b.hit.triangle, b.hit.u, b.hit.v), l1_q);
          if (reused && settings.reuse_diffuse_only) {
            // The screen holds only the view-independent part; the view-dependent rest is traced toward p.
            const Material& mq = scene.material_of(b.hit.triangle);
            if (mq.has_specular() || settings.blinn_k < 1.0f)
              l1_q += view_dependent_rest(traced, surface_of(scene, b), recompute, recompute_sampler,
                                          first_shadow_sample, rays_traced);
          }
        }
      }
      if (!reused && !cached) {
        traced_anew[traced_anew_count++] = k;
        continue;
      }
      const Vec3 contribution = bounce_contribution(material, sp, b.ray.dir, settings.blinn_k, l1_q);
      if (reused) {
        result.from_reused += contribution;
        ++result.reused;
      } else {
        result.from_cached += contribution;
        ++result.cached;
      }
    }

    if (traced_anew_count > 0) {
      // Their L1, the samples of several bounce hits sharing a batch's lanes: with `fill`'s rays where the result
      // goes to the store (a record for it, in the order of the bounces), with `recompute`'s elsewhere.
      std::array<const SurfacePoint*, kSampleBatch> points;
      std::array<uint64_t, kSampleBatch> first_samples;
      std::array<size_t, kSampleBatch> order;  // the fills first, then the rest, each in the order of the bounces
      size_t fill_count = 0;
      for (size_t j = 0; j < traced_anew_count; ++j)
        if (pending.items[traced_anew[j]].fills_store) order[fill_count++] = traced_anew[j];
      size_t n = fill_count;
      for (size_t j = 0; j < traced_anew_count; ++j)
        if (!pending.items[traced_anew[j]].fills_store) order[n++] = traced_anew[j];
      for (size_t j = 0; j < traced_anew_count; ++j) {
        PendingBounce& b = pending.items[order[j]];
        points[j] = &surface_of(scene, b);
        first_samples[j] = first_sample_of_run(b.sample, shadow_run);
      }
      std::array<Vec3, kSampleBatch> l1, arriving;
      if (fill_count > 0)
        estimate_direct_light_at_points(traced, points.data(), first_samples.data(), fill_count, fill,
                                        recompute_sampler, rays_traced, l1.data(), arriving.data());
      if (traced_anew_count > fill_count)
        estimate_direct_light_at_points(traced, points.data() + fill_count, first_samples.data() + fill_count,
                                        traced_anew_count - fill_count, recompute, recompute_sampler, rays_traced,
                                        l1.data() + fill_count);
      for (size_t j = 0; j < traced_anew_count; ++j) {
        const PendingBounce& b = pending.items[order[j]];
        if (j < fill_count)
          cache->records->push_back(
              make_l1_record(b.key, b.hash, arriving[j], static_cast<uint32_t>(std::max(fill.rays, 0))));
        result.from_recomputed += bounce_contribution(material, sp, b.ray.dir, settings.blinn_k, l1[j]);
      }
    }
  }
  const float inv = 1.0f / static_cast<float>(settings.l2_rays);
  result.from_reused *= inv;
  result.from_recomputed *= inv;
  result.from_cached *= inv;
  result.l2 = result.from_reused + result.from_recomputed + result.from_cached;
  return result;
}

Vec3 estimate_ambient_occlusion(const TracedScene& traced, const SurfacePoint& sp, int rays, float radius,
                                PixelSampler& sampler, uint64_t first_sample, uint64_t& rays_traced) {
  if (rays <= 0) return Vec3(0.0f);
  int open = 0;
  if (!reflects_light(traced.scene.material_of(sp.triangle))) return Vec3(0.0f);
  BounceDirections directions(sp);
  for (int batch = 0; batch < rays; batch += kSampleBatch) {
    const int count = std::min(kSampleBatch, rays - batch);
    directions.draw(sampler, first_sample + static_cast<uint64_t>(batch), count);
    for (size_t k = 0; k < static_cast<size_t>(count); ++k) {
      if (!directions.open(k)) continue;
      Ray ray = directions.ray(k);
      ray.tmax = radius;
      ++rays_traced;
      if (!intersect_any(traced.accel, ray)) ++open;
    }
  }
  return sp.albedo * (static_cast<float>(open) / static_cast<float>(rays));
}

float ambient_occlusion_radius(const TracedScene& traced, const RenderSettings& settings) {
  return settings.ao_radius > 0.0f ? settings.ao_radius : 0.1f * traced.diagonal;
}

}  // namespace lueur
