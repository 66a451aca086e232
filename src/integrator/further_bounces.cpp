// ln by path tracing from p (see further_bounces.h). Which vertex's light belongs to which pass: the light that
// reaches p directly is L1's; the light that a non-specular q, one bounce from p, receives by its shadow rays is
// L2's, and so is the emitter that q's bounce direction would meet; everything else is ln's. A mirror or glass
// vertex has no shadow ray that could find its light, so what its specular direction meets counts in full.
#include "integrator/further_bounces.h"

#include <algorithm>

#include "core/sampling.h"
#include "integrator/brdf.h"
#include "integrator/camera_path.h"
#include "integrator/direct_light.h"
#include "integrator/specular.h"

namespace lueur {
namespace {

/// The pairs of dimensions each vertex draws: (the lobe, Russian roulette), the bounce direction, (the emitter, -),
/// the point on the emitter.
constexpr uint32_t kPairsPerVertex = 4;
/// Russian roulette from this vertex on (p is 0): the first bounces keep their whole throughput.
constexpr uint32_t kRouletteVertex = 3;

float power_heuristic(float pdf, float other) {
  const float a = pdf * pdf, b = other * other;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

/// Next-event estimation at v: one point on an emitter chosen by power (the choice whose density any later vertex
/// can evaluate for the weights), its light through v's non-specular BRDF, weighted against v's bounce direction
/// finding the same light (`weigh`: a bounce follows; `bounce_probability`: the share of v's bounces that are not
/// specular, which scales their pdf). `arriving`, when given, receives the same sample's light arriving at v
/// without the BRDF or the weight (Le cos / pdf, 0 where hidden): an unbiased one-sample estimate for the L1 store.
Vec3 next_event(const TracedScene& traced, const SurfacePoint& v, const Material& m, float blinn_k,
                float bounce_probability, bool weigh, const Vec2& choice_u, const Vec2& point_u, uint64_t& rays,
                Vec3* arriving = nullptr) {
  const LightTable& table = traced.lights;
  if (table.empty()) return Vec3(0.0f);
  const LightChoice choice = choose_light(table, LightStrategy::kPower, choice_u.x);
  if (!(choice.pmf > 0.0f)) return Vec3(0.0f);
  const EmitterRecord& e = table.records[choice.index];
  const Vec2 b = sample_uniform_triangle(point_u.x, point_u.y);
  const Vec3 point = (1.0f - b.x - b.y) * e.p0 + b.x * e.p1 + b.y * e.p2;
  const Vec3 to_point = point - v.position;
  const float distance2 = glm::dot(to_point, to_point);
  if (!(distance2 > 0.0f)) return Vec3(0.0f);
  const Vec3 wi = to_point / std::sqrt(distance2);
  const float cos_light = -glm::dot(e.normal, wi);
  const float cos_surface = glm::dot(v.shading_normal, wi);
  if (cos_light <= 0.0f || cos_surface <= 0.0f || glm::dot(v.geometric_normal, wi) <= 0.0f) return Vec3(0.0f);
  const Vec3 origin = leaving_origin(v);
  if (!light_reaches(traced, origin, point - origin, rays)) return Vec3(0.0f);
  const float pdf = choice.pmf / e.area * distance2 / cos_light;  // solid angle, as sampled
  if (arriving) *arriving = e.ke * (cos_surface / pdf);
  float weight = 1.0f;
  if (weigh) {
    const float light_pdf = power_point_density(table, e.ke) * distance2 / cos_light;
    weight = power_heuristic(light_pdf, bounce_probability * cos_surface * kInvPi);
  }
  return eval_brdf(m, v.albedo, v.shading_normal, wi, v.wo, blinn_k) * e.ke * (cos_surface * weight / pdf);
}

/// What a vertex does about its L1: takes it whole (from the screen or a ready cell of the store), or traces its
/// shadow ray, feeding that sample to the store's cell `key` when `feeds`.
struct VertexL1 {
  enum Source { kShadowRay, kScreen, kStore } source = kShadowRay;
  Vec3 l1{0.0f};  ///< with kScreen or kStore
  bool feeds = false;
  L1CacheKey key;
  uint64_t hash = 0;
};

/// The jittered cell of the store at vertex v, and its hash: draws two of the pixel's look-up numbers.
void key_at_vertex(const L1CacheAccess& store, const SurfacePoint& v, L1CacheKey& key, uint64_t& hash) {
  const float u1 = store.jitter->next_float(), u2 = store.jitter->next_float();
  key = jittered_key(*store.grid, v.position, v.geometric_normal, u1, u2);
  hash = hash_of(key);
}

/// Where vertex v takes its L1 under further_bounces.h's rules: the store first (read where its cell is ready,
/// else fed by the vertex's own shadow ray), then the screen pixel that sees v.
VertexL1 l1_at_vertex(const TracedScene& traced, const RenderSettings& settings, const FurtherBounceReuse& reuse,
                      const SurfacePoint& v, const Material& m) {
  VertexL1 answer;
  if (settings.camera_light || !brdf_is_constant(m, settings.blinn_k, v.shading_normal, v.wo)) return answer;
  if (reuse.store) {
    const L1CacheAccess& store = *reuse.store;
    key_at_vertex(store, v, answer.key, answer.hash);
    const L1CacheCell* cell = nullptr;
    const StoreUse use = use_of_store(store, answer.key, answer.hash, cell);
    if (use == StoreUse::kRead) {
      answer.source = VertexL1::kStore;
      answer.l1 = constant_brdf(m, v.albedo, settings.blinn_k) * (cell->sum / static_cast<float>(cell->samples));
      return answer;
    }
    answer.feeds = use == StoreUse::kFeed;
  }
  if (reuse.screen && !settings.reuse_diffuse_only && m.diffuse_texture < 0) {
    const int pixel = find_reusable_pixel(*reuse.camera, *reuse.screen, v.triangle, v.position,
                                          traced.scene.geometric_normal_raw(v.triangle));
    if (pixel >= 0) {
      answer.source = VertexL1::kScreen;
      answer.l1 = reuse.screen->reused_l1(static_cast<size_t>(pixel), settings.reuse);
    }
  }
  return answer;
}

/// A path's feed of its further light to the cell at its first bounce hit.
struct FurtherFeed {
  bool feeds = false;
  L1CacheKey key;
  uint64_t hash = 0;
  Vec3 arriving{0.0f};  ///< the light found past q, over the path's throughput at q times q's BRDF
};

/// At a path's first bounce hit q (constant BRDF, the store modes): true and `further` set where q's cell holds
/// its further light (kFurtherMinSamples; the path ends there); otherwise false, and `feed` says whether the path,
/// going on, feeds the cell. The cell is the one L2 looked up at q where the path starts along L2's bounce (`first`).
bool further_at_first_bounce(const L1CacheAccess& store, const SurfacePoint& q, const SharedBounce* first,
                             FurtherFeed& feed, Vec3& further) {
  if (first && first->keyed) {
    feed.key = first->key;
    feed.hash = first->hash;
  } else {
    key_at_vertex(store, q, feed.key, feed.hash);
  }
  feed.key.light = kFurtherLight;  // the hash stays the L1 cell's: the slot L2 just read
  const L1CacheCell* cell = nullptr;
  const StoreUse use = further_use_of_store(store, feed.key, feed.hash, cell);
  if (use == StoreUse::kRead) {
    further = cell->sum / static_cast<float>(cell->samples);
    return true;
  }
  feed.feeds = use == StoreUse::kFeed;
  return false;
}

/// One path from p: its light beyond L1 and L2. `first`, when given, is its first segment, already traced.
Vec3 trace_path(const TracedScene& traced, const SurfacePoint& p, const RenderSettings& settings, int bounces_before,
                PixelSampler& sampler, uint64_t& rays, const SharedBounce* first, const FurtherBounceReuse& reuse,
                FurtherBounces& counts) {
  const Scene& scene = traced.scene;
  Vec3 light(0.0f), throughput(1.0f);
  SurfacePoint v = p;
  int bounces = bounces_before;  // scattering events before v
  bool after_specular = false;   // v was reached along a specular direction
  float bounce_pdf = 0.0f;       // otherwise, the solid-angle pdf of the direction that reached it
  bool whole_l1 = false;         // the vertex before v took its L1 whole (from the screen): v's emission is in it
  // Where the path feeds the store's cell at q its further light: the light it finds past q, over its throughput
  // at q times q's constant BRDF (`relative`: the throughput past q on that scale; zero while not feeding).
  FurtherFeed feed;
  Vec3 relative(0.0f);
  const auto add = [&](const Vec3& x) {
    light += throughput * x;
    feed.arriving += relative * x;
  };
  const auto scale = [&](const Vec3& factor) {
    throughput *= factor;
    relative *= factor;
  };
  // A feeding path draws its numbers past q from the pixel's look-up stream: a cell averages paths from many pixels'
  // first frames of a generation, a subset of their Sobol sequences that is not stratified, so its samples must be
  // independent ones.
  const auto draw = [&](uint32_t pair) {
    if (!feed.feeds) return sampler.get_2d_of_dimension(pair);
    const float a = reuse.store->jitter->next_float();
    return Vec2(a, reuse.store->jitter->next_float());
  };
  for (uint32_t vertex = 0;; ++vertex) {
    const Material& m = scene.material_of(v.triangle);
    const uint32_t pair = kPairsPerVertex * vertex;
    const Vec2 lobe_u = draw(pair);
    const bool scatters = bounces + 1 <= settings.max_bounces;
    // p scatters by its BRDF (a specular p: by its base, which the camera's path chose); later vertices by their
    // lobes.
    SpecularSample specular;
    const bool lobes = vertex > 0 && m.is_specular();
    if (lobes)
      specular = sample_specular(m, v.albedo, v.shading_normal, v.geometric_normal, v.wo, v.front_face, lobe_u.x);
    whole_l1 = false;
    if (vertex >= 2 && reflects_light(m)) {
      ++counts.lookups;
      const VertexL1 answer = lobes ? VertexL1{} : l1_at_vertex(traced, settings, reuse, v, m);
      if (answer.source != VertexL1::kShadowRay) {
        add(answer.l1);
        whole_l1 = true;
        counts.from_screen += answer.source == VertexL1::kScreen;
        counts.from_store += answer.source == VertexL1::kStore;
      } else {
        Vec3 arriving(0.0f);
        add(next_event(traced, v, m, settings.blinn_k, lobes ? specular.base_probability : 1.0f, scatters,
                       draw(pair + 2), draw(pair + 3), rays, answer.feeds ? &arriving : nullptr));
        if (answer.feeds) reuse.store->records->push_back(make_l1_record(answer.key, answer.hash, arriving, 1));
      }
    }
    if (vertex == 1 && bounces == 1 && reuse.store && !lobes && reflects_light(m) &&
        brdf_is_constant(m, settings.blinn_k, v.shading_normal, v.wo)) {
      Vec3 further(0.0f);
      if (further_at_first_bounce(*reuse.store, v, first, feed, further)) {
        light += throughput * constant_brdf(m, v.albedo, settings.blinn_k) * further;
        ++counts.ended_at_store;
        break;
      }
    }
    if (!scatters) break;
    if (vertex >= kRouletteVertex) {
      const float survival = std::min(1.0f, std::max({throughput.r, throughput.g, throughput.b}));
      if (!(lobe_u.y < survival)) break;
      scale(Vec3(1.0f / survival));
    }
    Vec3 dir(0.0f);
    if (vertex == 0 && first) {
      if (!first->open) break;
      dir = first->ray.dir;
      scale(eval_brdf(m, v.albedo, v.shading_normal, dir, v.wo, settings.blinn_k) * kPi);
      bounce_pdf = glm::dot(v.shading_normal, dir) * kInvPi;
      after_specular = false;
    } else if (lobes && specular.lobe != SpecularLobe::kBase) {
      if (specular.lobe == SpecularLobe::kNone) break;
      dir = specular.dir;
      scale(specular.weight);
      after_specular = true;
    } else {
      const Vec2 u = draw(pair + 1);
      const Vec3 local = sample_cosine_hemisphere(u.x, u.y);
      dir = Frame::from_normal(v.shading_normal).to_world(local);
      if (!(local.z > 0.0f) || glm::dot(dir, v.geometric_normal) <= 0.0f) break;
      // f cos / pdf: the base's albedo / its probability, or f pi for a BRDF sampled by its cosine.
      scale(lobes ? specular.weight : eval_brdf(m, v.albedo, v.shading_normal, dir, v.wo, settings.blinn_k) * kPi);
      bounce_pdf = (lobes ? specular.base_probability : 1.0f) * local.z * kInvPi;
      after_specular = false;
      // A feeding q's BRDF is constant and its direction cosine-sampled: f cos / pdf over that constant is pi.
      if (feed.feeds && vertex == 1) relative = Vec3(kPi);
    }
    if (!(std::max({throughput.r, throughput.g, throughput.b}) > 0.0f)) break;
    Ray ray;
    Hit hit;
    if (vertex == 0 && first) {
      ray = first->ray;
      hit = first->hit;
    } else {
      ray = leaving_ray(v.position, v.geometric_normal, dir);
      ++rays;
      hit = intersect_closest(traced.accel, ray);
    }
    ++bounces;
    if (!hit.found()) break;
    v = make_surface_point(scene, ray, hit);
    const Material& mv = scene.material_of(hit.triangle);
    if (v.front_face && mv.emissive()) {
      const uint32_t reached = vertex + 1;
      if (after_specular && reached >= 2) {
        add(mv.ke);
      } else if (!after_specular && reached >= 3 && !whole_l1) {
        const float cos_light = glm::dot(v.geometric_normal, v.wo);
        const float light_pdf = power_point_density(traced.lights, mv.ke) * hit.t * hit.t / cos_light;
        add(mv.ke * power_heuristic(bounce_pdf, light_pdf));
      }
    }
  }
  if (feed.feeds) reuse.store->records->push_back(make_l1_record(feed.key, feed.hash, feed.arriving, 1));
  return light;
}

}  // namespace

FurtherBounces estimate_further_bounces(const TracedScene& traced, const SurfacePoint& p,
                                        const RenderSettings& settings, int bounces_before, PixelSampler& sampler,
                                        uint64_t first_sample, uint64_t& rays_traced, const SharedBounce* shared,
                                        int shared_count, const FurtherBounceReuse& reuse) {
  FurtherBounces result;
  if (settings.ln_rays <= 0 || bounces_before + 2 > settings.max_bounces) return result;
  if (!reflects_light(traced.scene.material_of(p.triangle))) return result;
  Vec3 sum(0.0f);
  for (int k = 0; k < settings.ln_rays; ++k) {
    sampler.start_sample(first_sample + static_cast<uint64_t>(k));
    const SharedBounce* first = k < shared_count ? &shared[k] : nullptr;
    sum += trace_path(traced, p, settings, bounces_before, sampler, rays_traced, first, reuse, result);
  }
  result.paths = settings.ln_rays;
  result.light = sum / static_cast<float>(settings.ln_rays);
  return result;
}

}  // namespace lueur
