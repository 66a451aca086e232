// Whole frames timed through the renderer, on the benchmark's scenes and views.
#include "bench/bench_frame.h"

#include <algorithm>

#include "core/stopwatch.h"
#include "core/camera.h"
#include "film/film.h"
#include "integrator/renderer.h"
#include "integrator/traced_scene.h"

namespace lueur::bench {

FrameFigures measure_frames(const TracedScene& traced, const BenchScene& scene, int size, ThreadPool& pool,
                            double seconds) {
  RenderSettings settings;
  settings.width = settings.height = size;
  const Camera camera = make_camera(scene.view, size, size);
  Film film;
  film.reset(settings);
  render_frame(traced, camera, settings, film, nullptr, pool);  // warm-up: first touches of the tree and buffers

  FrameFigures figures;
  const Clock::time_point start = Clock::now();
  while (figures.frames < 2 || figures.seconds < seconds) {
    const FrameResult r = render_frame(traced, camera, settings, film, nullptr, pool);
    figures.primary += r.primary_rays;
    figures.bounce += r.bounce_rays;
    figures.any_hit += r.rays - r.primary_rays - r.bounce_rays;
    ++figures.frames;
    figures.seconds = seconds_since(start);
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

FrameComparison compare_frames_with_arrays(const BenchScene& scene, const Bvh& bvh, const RaySets& sets, int size,
                                           ThreadPool& pool, double seconds, const TimingOptions& timing) {
  const std::shared_ptr<const TracedScene> traced = prepare_scene(scene.scene);
  const int rounds = std::max(timing.rounds, 1);
  const TimingOptions one_round{timing.seconds_per_round, 1};
  FrameComparison c;
  std::vector<double> renderer, arrays;
  for (int round = 0; round < rounds; ++round) {
    const double primary = measure_throughput(sets.primary, Query::kClosest, bvh, nullptr, pool, one_round).lueur;
    const double bounce = measure_throughput(sets.bounce, Query::kClosest, bvh, nullptr, pool, one_round).lueur;
    const double shadow = measure_throughput(sets.shadow, Query::kAny, bvh, nullptr, pool, one_round).lueur;
    const FrameFigures f = measure_frames(*traced, scene, size, pool, seconds / rounds);
    const double mix = ray_mix_mrays(f, primary, bounce, shadow);
    renderer.push_back(f.renderer_mrays);
    arrays.push_back(mix);
    c.ratios.push_back(mix > 0.0 ? f.renderer_mrays / mix : 0.0);
    c.frames.frames += f.frames;
    c.frames.seconds += f.seconds;
    c.frames.primary += f.primary;
    c.frames.bounce += f.bounce;
    c.frames.any_hit += f.any_hit;
  }
  c.renderer_mrays = median(renderer);
  c.arrays_mrays = median(arrays);
  c.ratio = median(c.ratios);
  const auto total = static_cast<double>(c.frames.primary + c.frames.bounce + c.frames.any_hit);
  c.frames.renderer_mrays = c.frames.seconds > 0.0 ? total / c.frames.seconds * 1e-6 : 0.0;
  return c;
}

}  // namespace lueur::bench
