// One frame in two phases over the tiles. Phase 1: a jittered primary ray per pixel, followed through mirrors and
// glass to the pixel's p (camera_path.h), Le along the way, L1 and AO at p, and the screen buffer L2 reuses.
// Phase 2: L2, which may read any pixel's phase-1 L1, and ln, whose paths start along L2's bounce rays. Results go
// to per-frame buffers and are added to the film only once the whole frame has finished, so a cancelled frame
// leaves no trace and every pixel's sums see the same sequence of additions whatever the thread count.
#include "integrator/renderer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/stopwatch.h"
#include "integrator/camera_light.h"
#include "integrator/camera_path.h"
#include "integrator/direct_light.h"
#include "integrator/further_bounces.h"
#include "integrator/indirect_light.h"

namespace lueur {
namespace {

/// How the camera's path reached a pixel's p: what p's estimates are weighted by, and the bounces before it.
struct PathToP {
  Vec3 throughput{1.0f};
  int bounces = 0;
};

struct FrameBuffers {
  std::array<std::vector<Vec3>, kLayerCount> values;  ///< this frame's value per needed layer and pixel
  std::vector<SurfacePoint> hits;                     ///< p per pixel (triangle kNoHit: none)
  std::vector<PathToP> paths;                         ///< per pixel, how its p was reached
  ScreenBuffer screen;
};

uint64_t pixel_index(int x, int y, int width) {
  return static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x);
}

void set_layer(FrameBuffers& frame, Layer layer, size_t pixel, const Vec3& value) {
  auto& values = frame.values[static_cast<size_t>(layer)];
  if (!values.empty()) values[pixel] = value;
}

/// Le by `settings.le_rays` camera rays of their own (when there are more than one), each followed through mirrors
/// and glass: the sum of the emission they see. Emission is cheap to see and its edges are the sharpest in the image, so they get more camera rays per frame
/// than the shading does. They are one aligned block of one sequence per frame, not the pixel's primary ray plus
/// le_rays - 1 others: the primary's jitter is a sequence of its own (over frames), and three of each block of four
/// points are no net: a frame's missing point left Le's error falling as 1 / frames, where whole nets fall faster.
Vec3 emission_of_le_rays(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, int x, int y,
                         uint64_t pixel, uint64_t frame, uint64_t& rays, uint64_t& primary_rays) {
  const int count = settings.le_rays;
  Vec3 sum(0.0f);
  PixelSampler sampler(settings.sampler, settings.seed, pixel, frame, RngPurpose::kEmission);
  std::array<float, kSampleBatch> u1, u2;
  for (int batch = 0; batch < count; batch += kSampleBatch) {
    const int batch_count = std::min(kSampleBatch, count - batch);
    sampler.draw_2d(first_sample_of_run(frame, count) + static_cast<uint64_t>(batch), batch_count, u1.data(),
                    u2.data());
    for (size_t k = 0; k < static_cast<size_t>(batch_count); ++k) {
      const Ray ray = camera_ray(camera, static_cast<float>(x) + u1[k], static_cast<float>(y) + u2[k]);
      ++rays;
      ++primary_rays;
      // Vertex j's lobe: dimension 1 + j of the ray's sample (dimension 0 is its position in the pixel).
      sum += follow_camera_path(traced, ray, settings.max_bounces, sampler,
                                first_sample_of_run(frame, count) + static_cast<uint64_t>(batch) + k, 1, rays)
                 .emission;
    }
  }
  return sum;
}

/// The colour of a cell of the L1 store in the cache-cells view: its key hashed into RGB.
Vec3 cell_colour(const L1CacheKey& key) {
  const uint64_t h = hash_of(key);
  const auto channel = [h](int shift) { return static_cast<float>((h >> shift) & 0xffu) / 255.0f; };
  return Vec3(channel(0), channel(8), channel(16));
}

/// Phase 1 for one pixel. With a store grid, its L1 estimate becomes a record for the L1 store.
void trace_primary(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, const Film& film,
                   int x, int y, uint64_t frame, FrameBuffers& out, uint64_t& rays, uint64_t& primary_rays,
                   const L1CacheGrid* grid, std::vector<L1CacheRecord>* records) {
  const size_t i = pixel_index(x, y, camera.width);
  const uint64_t pixel = i;
  PixelSampler camera_sampler(settings.sampler, settings.seed, pixel, frame, RngPurpose::kCamera);
  camera_sampler.start_sample(frame);
  const Vec2 jitter = camera_sampler.get_2d();
  const Ray ray = camera_ray(camera, static_cast<float>(x) + jitter.x, static_cast<float>(y) + jitter.y);
  ++rays;
  ++primary_rays;
  const CameraPath path = follow_camera_path(traced, ray, settings.max_bounces, camera_sampler, frame, 1, rays);
  const bool le = settings.pass_enabled(Pass::kLe);
  // One Le ray: the primary's. More: rays of their own (emission_of_le_rays), the primary's emission unused.
  const bool le_of_own_rays = le && settings.le_rays > 1;
  if (le_of_own_rays) {
    const Vec3 emission = emission_of_le_rays(traced, camera, settings, x, y, pixel, frame, rays, primary_rays);
    set_layer(out, Layer::kLe, i, emission / static_cast<float>(settings.le_rays));
  }
  if (le && !le_of_own_rays) set_layer(out, Layer::kLe, i, path.emission);
  if (!path.hit.found()) return;

  const SurfacePoint sp = make_surface_point(traced.scene, path.ray, path.hit);
  const Vec3& throughput = path.throughput;
  out.hits[i] = sp;
  out.paths[i] = PathToP{throughput, path.bounces};
  // A p seen through a mirror or glass does not project to its pixel: the screen reuse must not find it there.
  if (!path.through_specular) {
    out.screen.triangle[i] = path.hit.triangle;
    out.screen.pixels[i].position = sp.position;
    out.screen.pixels[i].albedo = sp.albedo;
  }

  const bool l2 = settings.pass_enabled(Pass::kL2);
  const bool screen_needs_l1 = l2 && uses_screen(settings.reuse);
  if (grid)
    set_layer(out, Layer::kCacheCells, i,
              cell_colour(grid->key(sp.position, sp.geometric_normal, grid->level_at(sp.position))));
  if (settings.pass_enabled(Pass::kL1) || screen_needs_l1) {
    PixelSampler sampler(settings.sampler, settings.seed, pixel, frame, RngPurpose::kDirect);
    DirectLightOptions options;
    options.strategy = settings.lights;
    options.rays = settings.l1_rays;
    options.blinn_k = settings.blinn_k;
    EmitterRecord head_light;
    if (settings.camera_light) {
      head_light = make_camera_light(camera, traced.diagonal);
      options.camera_light = &head_light;
    }
    Vec3 diffuse(0.0f), arriving(0.0f);
    const Vec3 l1 = estimate_direct_light(traced, sp, options, sampler, first_sample_of_run(frame, options.rays), rays,
                                          &diffuse, grid ? &arriving : nullptr);
    if (grid && options.rays > 0) {
      Pcg32 cell_jitter = make_pixel_rng(settings.seed, pixel, frame, RngPurpose::kCacheFeed);
      const float u1 = cell_jitter.next_float(), u2 = cell_jitter.next_float();
      const L1CacheKey key = jittered_key(*grid, sp.position, sp.geometric_normal, u1, u2);
      records->push_back(make_l1_record(key, hash_of(key), arriving, static_cast<uint32_t>(options.rays)));
    }
    set_layer(out, Layer::kL1, i, throughput * l1);
    set_layer(out, Layer::kL1Diffuse, i, throughput * diffuse);
    const Vec3 screen_l1 = settings.reuse_diffuse_only ? diffuse : l1;
    out.screen.pixels[i].l1 = screen_l1;
    if (screen_needs_l1 && settings.reuse == ReuseMode::kAverage) {
      // The running average including this frame: less noisy than this frame alone.
      const auto& sums = film.sums[static_cast<size_t>(settings.reuse_diffuse_only ? Layer::kL1Diffuse : Layer::kL1)];
      const Vec3 previous(sums[3 * i], sums[3 * i + 1], sums[3 * i + 2]);
      out.screen.l1_average[i] = (previous + screen_l1) / static_cast<float>(film.frames + 1);
    }
  }
  if (settings.pass_enabled(Pass::kAo)) {
    PixelSampler sampler(settings.sampler, settings.seed, pixel, frame, RngPurpose::kOcclusion);
    set_layer(out, Layer::kAo, i,
              throughput * estimate_ambient_occlusion(traced, sp, settings.ao_rays,
                                                      ambient_occlusion_radius(traced, settings), sampler,
                                                      first_sample_of_run(frame, settings.ao_rays), rays));
  }
}

/// ln at pixel i's p, weighted by the camera path's throughput. Its vertices past q may take their L1 from the store
/// (`store`: the pixel's look-ups, the same as L2's) and the screen; their counts go to `counts`.
FurtherBounces trace_further_bounces(const TracedScene& traced, const Camera& camera, const RenderSettings& settings,
                                     const SurfacePoint& sp, const PathToP& path, size_t i, uint64_t frame,
                                     FrameBuffers& out, uint64_t& rays, const SharedBounce* shared, int shared_count,
                                     const L1CacheAccess* store) {
  PixelSampler sampler(settings.sampler, settings.seed, i, frame, RngPurpose::kPath);
  FurtherBounceReuse reuse;
  if (settings.pass_enabled(Pass::kL2) && uses_screen(settings.reuse)) {
    reuse.camera = &camera;
    reuse.screen = &out.screen;
  }
  reuse.store = store;
  const FurtherBounces result =
      estimate_further_bounces(traced, sp, settings, path.bounces, sampler,
                               first_sample_of_run(frame, settings.ln_rays), rays, shared, shared_count, reuse);
  set_layer(out, Layer::kLn, i, path.throughput * result.light);
  return result;
}

/// Per-worker counters, padded apart so that workers do not share cache lines.
struct alignas(64) WorkerCounters {
  uint64_t rays = 0, primary_rays = 0, bounce_rays = 0, bounce_hits = 0, reused = 0, cached = 0;
  uint64_t ln_lookups = 0, ln_reused = 0, ln_cached = 0, ln_paths = 0, ln_ended = 0;
  ServedSamples served;
};

/// Phase 2 for one pixel: L2, and ln, whose first paths start along L2's first bounce rays.
void trace_indirect(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, int x, int y,
                    uint64_t frame, FrameBuffers& out, WorkerCounters& counts, const L1Cache* store,
                    const L1CacheGrid* grid, std::vector<L1CacheRecord>* records) {
  uint64_t& rays = counts.rays;
  const size_t i = pixel_index(x, y, camera.width);
  const SurfacePoint& sp = out.hits[i];
  if (sp.triangle == kNoHit) return;
  const PathToP& path = out.paths[i];
  if (path.bounces + 1 > settings.max_bounces) return;  // L2's bounce would be one too many, and ln's
  const bool ln = settings.pass_enabled(Pass::kLn);
  std::array<SharedBounce, kSampleBatch> shared;
  const int shared_count = settings.pass_enabled(Pass::kL2) && ln
                               ? std::min({settings.ln_rays, settings.l2_rays, kSampleBatch})
                               : 0;
  if (!settings.pass_enabled(Pass::kL2)) {  // ln alone: its paths leave along bounces of their own
    trace_further_bounces(traced, camera, settings, sp, path, i, frame, out, rays, nullptr, 0, nullptr);
    return;
  }
  PixelSampler bounce_sampler(settings.sampler, settings.seed, i, frame, RngPurpose::kIndirect);
  PixelSampler recompute_sampler(settings.sampler, settings.seed, i, frame, RngPurpose::kRecompute);
  Pcg32 jitter(0, 0);
  L1CacheAccess access;
  if (store) {
    jitter = make_pixel_rng(settings.seed, i, frame, RngPurpose::kCacheLookup);
    access = L1CacheAccess{store, grid, &jitter, records, &counts.served};
  }
  const IndirectResult r = estimate_indirect_light(traced, camera, out.screen, sp, settings, bounce_sampler,
                                                   recompute_sampler, first_sample_of_run(frame, settings.l2_rays),
                                                   rays, store ? &access : nullptr, shared.data(), shared_count);
  const FurtherBounces further = ln ? trace_further_bounces(traced, camera, settings, sp, path, i, frame, out, rays,
                                                            shared.data(), shared_count, store ? &access : nullptr)
                                    : FurtherBounces{};
  set_layer(out, Layer::kL2, i, path.throughput * r.l2);
  set_layer(out, Layer::kL2Reused, i, path.throughput * r.from_reused);
  set_layer(out, Layer::kL2Recomputed, i, path.throughput * r.from_recomputed);
  set_layer(out, Layer::kL2Cached, i, path.throughput * r.from_cached);
  // Where the bounce hits (L2's) and the vertices past them (ln's) took L1 from, as shares: red the screen, green
  // the store, blue traced.
  const int lookups = r.bounce_hits + further.lookups;
  const int from_screen = r.reused + further.from_screen, from_store = r.cached + further.from_store;
  if (lookups > 0) {
    const auto share = [&](int n) { return static_cast<float>(n) / static_cast<float>(lookups); };
    set_layer(out, Layer::kReuseFraction, i,
              Vec3(share(from_screen), share(from_store), share(lookups - from_screen - from_store)));
  }
  counts.ln_lookups += static_cast<uint64_t>(further.lookups);
  counts.ln_reused += static_cast<uint64_t>(further.from_screen);
  counts.ln_cached += static_cast<uint64_t>(further.from_store);
  counts.ln_paths += static_cast<uint64_t>(further.paths);
  counts.ln_ended += static_cast<uint64_t>(further.ended_at_store);
  counts.bounce_rays += static_cast<uint64_t>(r.bounce_rays);
  counts.bounce_hits += static_cast<uint64_t>(r.bounce_hits);
  counts.reused += static_cast<uint64_t>(r.reused);
  counts.cached += static_cast<uint64_t>(r.cached);
}

/// Tiles across an image `size` pixels wide (or down one that high).
int tiles_across(int size) { return (size + kTileSize - 1) / kTileSize; }
int tile_count(int width, int height) { return tiles_across(width) * tiles_across(height); }

/// The tile (the task of for_each_tile) that pixel (x, y) belongs to.
int tile_of(int x, int y, int width) { return (y / kTileSize) * tiles_across(width) + x / kTileSize; }

/// Runs `per_pixel(x, y, worker)` over every pixel, one tile per task.
template <typename PerPixel>
void for_each_tile(ThreadPool& pool, int width, int height, const std::atomic<bool>* cancel, PerPixel&& per_pixel) {
  const int tiles_x = tiles_across(width);
  pool.parallel_for(tile_count(width, height), [&](int tile, int worker) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
    const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) per_pixel(x, y, worker);
  });
}

}  // namespace

double film_unit(const TracedScene& traced, const Camera& camera, const RenderSettings& settings) {
  float brightest = 1.0f;
  for (const EmitterRecord& emitter : traced.lights.records)
    brightest = std::max({brightest, emitter.ke.r, emitter.ke.g, emitter.ke.b});
  if (settings.camera_light) {
    const Vec3 ke = make_camera_light(camera, traced.diagonal).ke;
    brightest = std::max({brightest, ke.r, ke.g, ke.b});
  }
  if (!std::isfinite(brightest)) brightest = std::numeric_limits<float>::max();
  int exponent = 0;
  std::frexp(brightest, &exponent);  // brightest < 2^exponent
  return std::ldexp(1.0, exponent - 32);
}

uint64_t frames_before_samples_repeat(const RenderSettings& settings) {
  const auto run = [](int count) { return std::bit_ceil(static_cast<uint64_t>(std::max(count, 1))); };
  const std::array<bool, kLayerCount> layers = layers_needed(settings);
  uint64_t longest = 1;  // the camera's jitter: one sample a frame
  if (settings.pass_enabled(Pass::kLe)) longest = std::max(longest, run(settings.le_rays));
  if (layers[static_cast<size_t>(Layer::kL1)] || settings.pass_enabled(Pass::kL2)) longest = std::max(longest, run(settings.l1_rays));
  if (settings.pass_enabled(Pass::kAo)) longest = std::max(longest, run(settings.ao_rays));
  if (settings.pass_enabled(Pass::kLn)) longest = std::max(longest, run(settings.ln_rays));
  if (settings.pass_enabled(Pass::kL2)) {
    // indirect_light.cpp: each bounce's shadow rays are a run as long as the longest estimate a bounce may trace.
    const int shadow_run = std::max(settings.recompute_rays(), uses_cache(settings.reuse) ? kL1CacheFillRays : 0);
    longest = std::max(longest, run(settings.l2_rays) * run(shadow_run));
  }
  return (uint64_t{1} << 32) / longest;
}

uint64_t l1_store_bytes(const RenderSettings& settings) {
  if (!settings.pass_enabled(Pass::kL2) || !uses_cache(settings.reuse)) return 0;
  return static_cast<uint64_t>(std::max(settings.cache_mb, 0)) << 20;
}

FrameResult render_frame(const TracedScene& traced, const Camera& camera, const RenderSettings& requested, Film& film,
                         L1Cache* l1_store, ThreadPool& pool, const std::atomic<bool>* cancel) {
  FrameResult result;
  const int width = film.width, height = film.height;
  const uint64_t frame = film.frames;
  RenderSettings settings = requested;
  if (settings.reuse == ReuseMode::kScreenCache && frame >= kScreenCacheFrames) settings.reuse = ReuseMode::kCache;
  if (film.unit == 0.0) film.unit = film_unit(traced, camera, settings);
  if (film.mode == FilmMode::kExactOnly && settings.pass_enabled(Pass::kL2) && settings.reuse == ReuseMode::kAverage)
    throw std::logic_error("render_frame: --reuse average reads the film's float sums, which this film does not keep");

  FrameBuffers buffers;
  for (int l = 0; l < kLayerCount; ++l)
    if (film.has(static_cast<Layer>(l))) buffers.values[static_cast<size_t>(l)].assign(film.pixel_count(), Vec3(0.0f));
  SurfacePoint none;
  none.triangle = kNoHit;
  buffers.hits.assign(film.pixel_count(), none);
  buffers.paths.assign(film.pixel_count(), PathToP{});
  buffers.screen.resize(width, height);
  if (settings.pass_enabled(Pass::kL2) && settings.reuse == ReuseMode::kAverage)
    buffers.screen.l1_average.assign(film.pixel_count(), Vec3(0.0f));

  // The L1 store: read as the previous frames left it, while this frame's estimates wait in per-tile records (phase
  // 1's tiles, then phase 2's) to be merged in that order at the end. A new generation starts it afresh, smaller.
  const bool store = settings.pass_enabled(Pass::kL2) && uses_cache(settings.reuse);
  if (store && !l1_store)
    throw std::invalid_argument("render_frame: --reuse " + std::string(enum_name(kReuseModeNames, settings.reuse)) +
                                " needs an L1 store");
  L1CacheGrid grid;
  const int tiles = tile_count(width, height);
  std::vector<std::vector<L1CacheRecord>> records(store ? 2 * static_cast<size_t>(tiles) : 0);
  if (store) {
    int generation = l1_cache_generation(frame);
    // A store whose next generation would not fit keeps its cells, which go on learning, rather than refusing most
    // of the smaller ones (their hits would be traced as without a store).
    if (l1_store->generation >= 0 && generation > l1_store->generation && !l1_store->has_room_for_next_generation())
      generation = l1_store->generation;
    if (l1_store->generation != generation) {
      l1_store->clear();
      l1_store->generation = generation;
    }
    grid = make_l1_cache_grid(camera, traced.lower, traced.diagonal, settings.cache_cell_pixels_in_use(), generation);
  }
  const auto tile_records = [&](int phase, int x, int y) {
    return &records[static_cast<size_t>(phase * tiles + tile_of(x, y, width))];
  };

  std::vector<WorkerCounters> counters(static_cast<size_t>(pool.thread_count()));
  for_each_tile(pool, width, height, cancel, [&](int x, int y, int worker) {
    WorkerCounters& c = counters[static_cast<size_t>(worker)];
    trace_primary(traced, camera, settings, film, x, y, frame, buffers, c.rays, c.primary_rays, store ? &grid : nullptr,
                  store ? tile_records(0, x, y) : nullptr);
  });
  if (settings.pass_enabled(Pass::kL2) || settings.pass_enabled(Pass::kLn)) {
    const Clock::time_point l2_start = Clock::now();
    for_each_tile(pool, width, height, cancel, [&](int x, int y, int worker) {
      WorkerCounters& c = counters[static_cast<size_t>(worker)];
      trace_indirect(traced, camera, settings, x, y, frame, buffers, c, store ? l1_store : nullptr,
                     store ? &grid : nullptr, store ? tile_records(1, x, y) : nullptr);
    });
    result.l2_seconds = seconds_since(l2_start);
  }
  for (const WorkerCounters& c : counters) {
    result.rays += c.rays;
    result.primary_rays += c.primary_rays;
    result.bounce_rays += c.bounce_rays;
    result.l2_bounce_hits += c.bounce_hits;
    result.l2_reused += c.reused;
    result.l2_cached += c.cached;
    result.ln_lookups += c.ln_lookups;
    result.ln_reused += c.ln_reused;
    result.ln_cached += c.ln_cached;
    result.ln_paths += c.ln_paths;
    result.ln_ended += c.ln_ended;
    result.served_samples.add(c.served);
  }

  if (cancel && cancel->load()) {
    result.completed = false;
    return result;
  }
  if (store) {
    l1_store->merge(records, pool);
    result.cache = l1_store->stats();
  }
  result.dropped_samples = film.add_frame(buffers.values);
  return result;
}

}  // namespace lueur
