// One frame: a jittered primary ray per pixel, then the enabled passes at its first hit. Each pixel's results are
// written to a frame buffer and added to the film only once the whole frame has finished, so a cancelled frame
// leaves no trace.
#include "render/renderer.h"

#include "render/direct_light.h"

namespace lueur {
namespace {

struct PixelSamples {
  std::array<Vec3, kPassCount> value{};
};

/// Everything one pixel contributes to one frame.
PixelSamples trace_pixel(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, int x,
                         int y, uint64_t frame, uint64_t& rays) {
  PixelSamples out;
  const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(camera.width) + static_cast<uint64_t>(x);
  Pcg32 camera_rng = make_pixel_rng(settings.seed, pixel, frame, RngPurpose::kCamera);
  const float jx = camera_rng.next_float(), jy = camera_rng.next_float();
  const Ray ray = camera_ray(camera, static_cast<float>(x) + jx, static_cast<float>(y) + jy);
  ++rays;
  const Hit hit = intersect_closest(traced.bvh, ray);
  if (!hit.found()) return out;

  const SurfacePoint sp = make_surface_point(traced.scene, ray, hit);
  const Material& material = traced.scene.material_of(hit.triangle);
  if (settings.pass_enabled(Pass::kLe) && sp.front_face) out.value[static_cast<size_t>(Pass::kLe)] = material.ke;

  if (settings.pass_enabled(Pass::kL1)) {
    Pcg32 rng = make_pixel_rng(settings.seed, pixel, frame, RngPurpose::kDirect);
    DirectLightOptions options;
    options.strategy = settings.lights;
    options.rays = settings.l1_rays;
    options.blinn_k = settings.blinn_k;
    out.value[static_cast<size_t>(Pass::kL1)] = estimate_direct_light(traced, sp, options, rng, rays);
  }
  return out;
}

}  // namespace

FrameResult render_frame(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, Film& film,
                         ThreadPool& pool, const std::atomic<bool>* cancel) {
  FrameResult result;
  const int width = film.width, height = film.height;
  const int tiles_x = (width + kTileSize - 1) / kTileSize, tiles_y = (height + kTileSize - 1) / kTileSize;
  const uint64_t frame = film.frames;

  std::array<std::vector<Vec3>, kPassCount> frame_values;
  for (int p = 0; p < kPassCount; ++p)
    if (film.has(static_cast<Pass>(p))) frame_values[static_cast<size_t>(p)].assign(film.pixel_count(), Vec3(0.0f));

  std::vector<uint64_t> worker_rays(static_cast<size_t>(pool.thread_count()), 0);
  pool.parallel_for(tiles_x * tiles_y, [&](int tile, int worker) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
    const int x1 = std::min(x0 + kTileSize, width), y1 = std::min(y0 + kTileSize, height);
    uint64_t rays = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const PixelSamples s = trace_pixel(traced, camera, settings, x, y, frame, rays);
        const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
        for (size_t p = 0; p < kPassCount; ++p)
          if (!frame_values[p].empty()) frame_values[p][i] = s.value[p];
      }
    worker_rays[static_cast<size_t>(worker)] += rays;
  });
  for (const uint64_t r : worker_rays) result.rays += r;

  if (cancel && cancel->load()) {
    result.completed = false;
    return result;
  }
  for (size_t p = 0; p < kPassCount; ++p) {
    if (frame_values[p].empty()) continue;
    float* sum = film.sums[p].data();
    for (size_t i = 0; i < frame_values[p].size(); ++i) {
      sum[3 * i] += frame_values[p][i].r;
      sum[3 * i + 1] += frame_values[p][i].g;
      sum[3 * i + 2] += frame_values[p][i].b;
    }
  }
  ++film.frames;
  return result;
}

}  // namespace lueur
