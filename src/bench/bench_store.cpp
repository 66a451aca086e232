// The reuse modes raced against each other. Every mode renders the default passes with its defaults; the errors are
// the RMSE of the L2 layer, and the RMSE and issue 8's relMSE of the image (Le + 0.6 L1 + 0.4 L2), against a
// reference rendered with `off` (the unbiased estimator) and another seed. The image's RMSE is dominated by the few
// pixels on the light's edge (on the default scene at 128x128, 10 pixels hold 60-70% of its squared error), whose Le
// is the same frame for frame in every mode: its relMSE is the figure that compares modes. The time to reach `frame`'s
// final L2 error is the first frame's time at which a mode's L2 error is at or below it, on the clock of its own
// frames (the error computations and the other modes' turns are taken out: the modes take turns of a few seconds).
#include "bench/bench_store.h"

#include <chrono>
#include <optional>
#include <string>

#include "bench/bench_convergence.h"
#include "integrator/renderer.h"
#include "scene/obj_loader.h"

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
  L1Cache l1_store;
  std::vector<Point> curve;                                   ///< after every frame
  uint64_t bounce_hits = 0, from_screen = 0, from_store = 0;  ///< where L2's bounce hits took L1, over the run
  L1CacheStats store;                                         ///< the store after the last frame
};

/// A mode's frames, timed one by one: `seconds` counts only its render_frame calls (not the error computations, nor
/// the other modes' turns).
struct Racer {
  RenderSettings settings;
  Run run;
  double seconds = 0.0;

  explicit Racer(const RenderSettings& s) : settings(s) {
    run.film.reset(s);
    run.l1_store.reset(l1_store_bytes(s));
  }

  /// Frames until this racer's own clock passes `until` seconds, the errors after each one (when references are
  /// given).
  void render_until(const TracedScene& traced, const Camera& camera, ThreadPool& pool, double until,
                    const Image* l2_reference, const Image* image_reference) {
    while (seconds < until) {
      const Clock::time_point start = Clock::now();
      const FrameResult frame = render_frame(traced, camera, settings, run.film, &run.l1_store, pool);
      seconds += std::chrono::duration<double>(Clock::now() - start).count();
      run.bounce_hits += frame.l2_bounce_hits;
      run.from_screen += frame.l2_reused;
      run.from_store += frame.l2_cached;
      run.store = frame.cache;
      if (l2_reference) {
        const Image image = image_of(run.film, settings);
        run.curve.push_back({seconds, image_rmse(layer_average(run.film, Layer::kL2), *l2_reference),
                             image_rmse(image, *image_reference), image_relmse(image, *image_reference)});
      } else {
        run.curve.push_back({seconds, 0.0, 0.0, 0.0});
      }
    }
  }
};

/// Every mode renders for `seconds` of its own frames' time, the modes taking turns of `turn` seconds each, so that
/// a change in the host's speed (other tenants of a shared machine move it by 10-30% within minutes) falls on every
/// mode alike rather than on whichever ran then.
std::vector<Run> race(const TracedScene& traced, const Camera& camera, const std::vector<RenderSettings>& modes,
                      ThreadPool& pool, double seconds, double turn, const Image* l2_reference,
                      const Image* image_reference) {
  std::vector<Racer> racers;
  racers.reserve(modes.size());
  for (const RenderSettings& s : modes) racers.emplace_back(s);
  if (!(turn > 0.0)) turn = seconds;
  for (double until = std::min(turn, seconds);; until = std::min(until + turn, seconds)) {
    for (Racer& r : racers) r.render_until(traced, camera, pool, until, l2_reference, image_reference);
    if (until >= seconds) break;
  }
  std::vector<Run> runs;
  for (Racer& r : racers) runs.push_back(std::move(r.run));
  return runs;
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
    // Under the rig's panel the room is lit as the viewer lights it; the scene is read again, with the rig.
    const bool rig = o.conference_rig && b.name == "conference";
    const auto traced = prepare_scene(rig ? load_obj(b.path).scene : b.scene);
    const std::string light = b.name != "conference" ? "" : rig ? "rig" : "bench";
    const Camera camera = make_camera(b.view, o.size, o.size);
    RenderSettings base;
    base.width = base.height = o.size;

    RenderSettings reference_settings = base;
    reference_settings.reuse = ReuseMode::kOff;
    reference_settings.seed = 1000;
    const Run reference =
        race(*traced, camera, {reference_settings}, pool, o.reference_seconds, o.reference_seconds, nullptr, nullptr)
            .front();
    const Image l2_reference = layer_average(reference.film, Layer::kL2);
    const Image image_reference = image_of(reference.film, reference_settings);
    std::fprintf(log, "lueur-bench: store %s%s: reference (reuse off) %llu frames in %.1f s\n", b.name.c_str(),
                 rig ? " under the rig's panel" : "", static_cast<unsigned long long>(reference.film.frames),
                 reference.curve.back().seconds);

    const ReuseMode modes[] = {ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kCache, ReuseMode::kScreenCache};
    std::vector<RenderSettings> settings;
    for (const ReuseMode mode : modes) {
      RenderSettings s = base;
      s.reuse = mode;
      s.seed = 1;
      s.cache_cell_pixels = o.cell_pixels;
      settings.push_back(s);
    }
    const std::vector<Run> runs =
        race(*traced, camera, settings, pool, o.seconds, o.turn_seconds, &l2_reference, &image_reference);
    const double frame_l2 = runs[1].curve.back().l2;  // `frame` at the end of its time
    for (size_t m = 0; m < runs.size(); ++m) {
      const Run& r = runs[m];
      const Point& end = r.curve.back();
      const std::optional<double> reach = time_to_reach(r.curve, frame_l2);
      const std::string mode(kReuseModeNames[static_cast<size_t>(modes[m])]);
      const Json cell_pixels = uses_cache(modes[m]) ? Json(settings[m].cache_cell_pixels_in_use()) : Json(nullptr);
      results.push_back(Json{{"scene", b.name},
                             {"light", light.empty() ? Json(nullptr) : Json(light)},
                             {"size", o.size},
                             {"reuse", mode},
                             {"frames", r.film.frames},
                             {"seconds", end.seconds},
                             {"l2_rmse", end.l2},
                             {"image_rmse", end.image},
                             {"image_relmse", end.image_relmse},
                             {"seconds_to_frame_l2_rmse", reach ? Json(*reach) : Json(nullptr)},
                             {"reference_frames", reference.film.frames},
                             {"cache_cell_pixels", cell_pixels},
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
