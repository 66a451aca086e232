// ln's error by time, with and without the L1 store (see bench_store_ln.h).
#include "bench/bench_store_ln.h"

#include <chrono>
#include <optional>

#include "bench/bench_convergence.h"
#include "integrator/renderer.h"

namespace lueur::bench {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

struct Point {
  double seconds, ln_mse;
};

/// One mode's render, timed frame by frame on its own clock.
struct Racer {
  RenderSettings settings;
  Accumulation accumulation;
  std::vector<Point> curve;
  double seconds = 0.0;
  uint64_t lookups = 0, from_screen = 0, from_store = 0, paths = 0, ended = 0;

  explicit Racer(const RenderSettings& s) : settings(s) { accumulation.reset(s); }

  void render_until(const TracedScene& traced, const Camera& camera, ThreadPool& pool, double until,
                    const Image* reference, double reference_noise) {
    while (seconds < until) {
      const Clock::time_point start = Clock::now();
      const FrameResult r = render_frame(traced, camera, settings, accumulation, pool);
      seconds += std::chrono::duration<double>(Clock::now() - start).count();
      lookups += r.ln_lookups;
      from_screen += r.ln_reused;
      from_store += r.ln_cached;
      paths += r.ln_paths;
      ended += r.ln_ended;
      if (reference)
        curve.push_back(
            {seconds, image_mse(layer_average(accumulation.film, Layer::kLn), *reference) - reference_noise});
    }
  }
};

RenderSettings every_light_pass(int size, ReuseMode reuse, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = size;
  s.enabled = {true, true, true, false, true};
  s.max_bounces = 8;
  s.reuse = reuse;
  s.seed = seed;
  return s;
}

double share(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

}  // namespace

Json run_store_ln(std::vector<BenchScene>& scenes, const StoreLnOptions& o, std::FILE* log) {
  Json results = Json::array();
  ThreadPool pool(o.threads);
  for (BenchScene& b : scenes) {
    if (b.name != "conference" && b.name != "cornell-original") continue;
    const auto traced = prepare_scene(b.scene);
    const Camera camera = make_camera(b.view, o.size, o.size);

    Image halves[2];
    uint64_t reference_frames = 0;
    for (int h = 0; h < 2; ++h) {
      Racer reference(every_light_pass(o.size, ReuseMode::kOff, 1000 + static_cast<uint64_t>(h)));
      reference.render_until(*traced, camera, pool, o.reference_seconds, nullptr, 0.0);
      halves[h] = layer_average(reference.accumulation.film, Layer::kLn);
      reference_frames += reference.accumulation.film.frames;
    }
    const TwoRenderReference two = reference_of_two(halves[0], halves[1]);
    const Image& reference = two.mean;
    const double reference_noise = two.noise;
    std::fprintf(log, "lueur-bench: store-ln %s: reference (reuse off) %llu frames, noise %.3g\n", b.name.c_str(),
                 static_cast<unsigned long long>(reference_frames), reference_noise);

    const ReuseMode modes[] = {ReuseMode::kOff, ReuseMode::kCache, ReuseMode::kScreenCache};
    std::vector<Racer> racers;
    racers.reserve(std::size(modes));
    for (const ReuseMode mode : modes) racers.emplace_back(every_light_pass(o.size, mode, 1));
    for (double until = std::min(o.turn_seconds, o.seconds);; until = std::min(until + o.turn_seconds, o.seconds)) {
      for (Racer& r : racers) r.render_until(*traced, camera, pool, until, &reference, reference_noise);
      if (until >= o.seconds) break;
    }
    const double off_error = racers[0].curve.back().ln_mse;
    for (size_t m = 0; m < racers.size(); ++m) {
      const Racer& r = racers[m];
      std::optional<double> reach;
      for (const Point& p : r.curve)
        if (p.ln_mse <= off_error) {
          reach = p.seconds;
          break;
        }
      const std::string mode(kReuseModeNames[static_cast<size_t>(modes[m])]);
      results.push_back(Json{{"scene", b.name},
                             {"size", o.size},
                             {"reuse", mode},
                             {"frames", r.accumulation.film.frames},
                             {"seconds", r.seconds},
                             {"ln_mse", r.curve.back().ln_mse},
                             {"seconds_to_off_ln_mse", reach ? Json(*reach) : Json(nullptr)},
                             {"reference_frames", reference_frames},
                             {"reference_noise", reference_noise},
                             {"ln_share_from_screen", share(r.from_screen, r.lookups)},
                             {"ln_share_from_store", share(r.from_store, r.lookups)},
                             {"ln_paths_ended_by_store", share(r.ended, r.paths)}});
      std::fprintf(log,
                   "lueur-bench: store-ln %-16s %-13s %5llu frames in %5.1f s: ln MSE %.4g; off's (%.4g) reached %s; "
                   "ln's vertices %.0f%% screen, %.0f%% store; paths ended by the store %.0f%%\n",
                   b.name.c_str(), mode.c_str(), static_cast<unsigned long long>(r.accumulation.film.frames), r.seconds,
                   r.curve.back().ln_mse, off_error,
                   reach ? (std::to_string(*reach).substr(0, 6) + " s").c_str() : "never",
                   100.0 * share(r.from_screen, r.lookups), 100.0 * share(r.from_store, r.lookups),
                   100.0 * share(r.ended, r.paths));
      std::fflush(log);
    }
  }
  return results;
}

}  // namespace lueur::bench
