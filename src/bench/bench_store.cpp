// The reuse modes raced against each other. Every mode renders the default passes with its defaults; the errors are
// the RMSE of the L2 layer, and the RMSE and issue 8's relMSE of the image (Le + 0.6 L1 + 0.4 L2), against a
// reference rendered with `off` (the unbiased estimator) and another seed. The image's RMSE is dominated by the few
// pixels on the light's edge (on the default scene at 128x128, 10 pixels hold 60-70% of its squared error), whose Le
// is the same frame for frame in every mode: its relMSE is the figure that compares modes. The time to reach `frame`'s
// final L2 error is the first frame's time at which a mode's L2 error is at or below it, on the clock of its own run
// (the error computations are taken out).
#include "bench/bench_store.h"

#include <chrono>
#include <optional>
#include <string>

#include "bench/bench_convergence.h"
#include "render/renderer.h"

namespace lueur::bench {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

Image image_of(const Film& film, const RenderSettings& settings) {
  return combine_passes(film, settings.enabled, kReportWeights);
}

struct Point {
  double seconds, l2, image, image_relmse;
};

struct Run {
  Film film;
  std::vector<Point> curve;                                   ///< after every frame
  uint64_t bounce_hits = 0, from_screen = 0, from_store = 0;  ///< where L2's bounce hits took L1, over the run
  L1CacheStats store;                                         ///< the store after the last frame
};

/// Frames of `settings` until `seconds` have passed, the errors after each one (when references are given).
Run race(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, ThreadPool& pool,
         double seconds, const Image* l2_reference, const Image* image_reference) {
  Run run;
  run.film.reset(settings);
  const Clock::time_point start = Clock::now();
  Clock::duration paused{0};
  while (true) {
    const FrameResult frame = render_frame(traced, camera, settings, run.film, pool);
    run.bounce_hits += frame.l2_bounce_hits;
    run.from_screen += frame.l2_reused;
    run.from_store += frame.l2_cached;
    run.store = frame.cache;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start - paused).count();
    if (l2_reference) {
      const Clock::time_point pause = Clock::now();
      const Image image = image_of(run.film, settings);
      run.curve.push_back({elapsed, image_rmse(layer_average(run.film, Layer::kL2), *l2_reference),
                           image_rmse(image, *image_reference), image_relmse(image, *image_reference)});
      paused += Clock::now() - pause;
    } else {
      run.curve.push_back({elapsed, 0.0, 0.0, 0.0});
    }
    if (elapsed >= seconds) break;
  }
  return run;
}

double share(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

std::optional<double> time_to_reach(const std::vector<Point>& curve, double l2_error) {
  for (const Point& p : curve)
    if (p.l2 <= l2_error) return p.seconds;
  return std::nullopt;
}

}  // namespace

Json run_store_comparison(std::vector<BenchScene>& scenes, const StoreOptions& o, std::FILE* log) {
  Json results = Json::array();
  ThreadPool pool(o.threads);
  for (BenchScene& b : scenes) {
    if (b.name != "default" && b.name != "conference") continue;
    const auto traced = prepare_scene(b.scene);
    const Camera camera = make_camera(b.view, o.size, o.size);
    RenderSettings base;
    base.width = base.height = o.size;

    RenderSettings reference_settings = base;
    reference_settings.reuse = ReuseMode::kOff;
    reference_settings.seed = 1000;
    const Run reference = race(*traced, camera, reference_settings, pool, o.reference_seconds, nullptr, nullptr);
    const Image l2_reference = layer_average(reference.film, Layer::kL2);
    const Image image_reference = image_of(reference.film, reference_settings);
    std::fprintf(log, "lueur-bench: store %s: reference (reuse off) %llu frames in %.1f s\n", b.name.c_str(),
                 static_cast<unsigned long long>(reference.film.frames), reference.curve.back().seconds);

    std::vector<Run> runs;
    const ReuseMode modes[] = {ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kCache, ReuseMode::kScreenCache};
    for (const ReuseMode mode : modes) {
      RenderSettings s = base;
      s.reuse = mode;
      s.seed = 1;
      runs.push_back(race(*traced, camera, s, pool, o.seconds, &l2_reference, &image_reference));
    }
    const double frame_l2 = runs[1].curve.back().l2;  // `frame` at the end of its time
    for (size_t m = 0; m < runs.size(); ++m) {
      const Run& r = runs[m];
      const Point& end = r.curve.back();
      const std::optional<double> reach = time_to_reach(r.curve, frame_l2);
      const std::string mode(kReuseModeNames[static_cast<size_t>(modes[m])]);
      results.push_back(Json{{"scene", b.name},
                             {"size", o.size},
                             {"reuse", mode},
                             {"frames", r.film.frames},
                             {"seconds", end.seconds},
                             {"l2_rmse", end.l2},
                             {"image_rmse", end.image},
                             {"image_relmse", end.image_relmse},
                             {"seconds_to_frame_l2_rmse", reach ? Json(*reach) : Json(nullptr)},
                             {"reference_frames", reference.film.frames},
                             {"cache_cells", r.store.cells},
                             {"cache_full", r.store.full},
                             {"share_from_screen", share(r.from_screen, r.bounce_hits)},
                             {"share_from_store", share(r.from_store, r.bounce_hits)}});
      std::fprintf(log,
                   "lueur-bench: store %-10s %-13s %5llu frames in %5.1f s: L2 RMSE %.6f, image RMSE %.6f relMSE %.3g; "
                   "frame's L2 error (%.6f) reached %s; bounce hits %.0f%% screen, %.0f%% store; %llu cells%s\n",
                   b.name.c_str(), mode.c_str(), static_cast<unsigned long long>(r.film.frames), end.seconds, end.l2,
                   end.image, end.image_relmse, frame_l2,
                   reach ? (std::to_string(*reach).substr(0, 6) + " s").c_str() : "never",
                   100.0 * share(r.from_screen, r.bounce_hits), 100.0 * share(r.from_store, r.bounce_hits),
                   static_cast<unsigned long long>(r.store.cells), r.store.full ? " (full)" : "");
    }
  }
  return results;
}

}  // namespace lueur::bench
