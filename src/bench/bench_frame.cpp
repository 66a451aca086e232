// Whole frames timed through the renderer, on the benchmark's scenes and views.
#include "bench/bench_frame.h"

#include <chrono>

#include "render/camera.h"
#include "render/film.h"
#include "render/renderer.h"
#include "render/traced_scene.h"

namespace lueur::bench {

FrameFigures measure_frames(const BenchScene& scene, int size, ThreadPool& pool, double seconds) {
  using Clock = std::chrono::steady_clock;
  const std::shared_ptr<const TracedScene> traced = prepare_scene(scene.scene);
  RenderSettings settings;
  settings.width = settings.height = size;
  const Camera camera = make_camera(scene.view, size, size);
  Film film;
  film.reset(settings);
  render_frame(*traced, camera, settings, film, pool);  // warm-up: first touches of the tree and buffers

  FrameFigures figures;
  const Clock::time_point start = Clock::now();
  while (figures.frames < 2 || figures.seconds < seconds) {
    const FrameResult r = render_frame(*traced, camera, settings, film, pool);
    figures.primary += r.primary_rays;
    figures.bounce += r.bounce_rays;
    figures.any_hit += r.rays - r.primary_rays - r.bounce_rays;
    ++figures.frames;
    figures.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  const auto total = static_cast<double>(figures.primary + figures.bounce + figures.any_hit);
  figures.renderer_mrays = figures.seconds > 0.0 ? total / figures.seconds * 1e-6 : 0.0;
  return figures;
}

double ray_mix_mrays(const FrameFigures& frames, double primary_mrays, double bounce_mrays, double shadow_mrays) {
  if (!(primary_mrays > 0.0 && bounce_mrays > 0.0 && shadow_mrays > 0.0)) return 0.0;
  const auto primary = static_cast<double>(frames.primary), bounce = static_cast<double>(frames.bounce),
             any_hit = static_cast<double>(frames.any_hit);
  const double microseconds = primary / primary_mrays + bounce / bounce_mrays + any_hit / shadow_mrays;
  return microseconds > 0.0 ? (primary + bounce + any_hit) / microseconds : 0.0;
}

}  // namespace lueur::bench
