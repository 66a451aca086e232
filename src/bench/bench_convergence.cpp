// Equal-time convergence runs. Light strategies render L1 alone with one shadow ray per pixel per frame (so that
// even `all`, one ray per emitter, finishes frames often); reuse modes render the default passes (Le + 0.6 L1 +
// 0.4 L2, 16 rays each). Every variant is compared with a reference rendered with another seed: for strategies,
// `area` (all four are unbiased); for reuse, `off` (unbiased), so that the bias of reuse shows in its RMSE.
#include "bench/bench_convergence.h"

#include <chrono>
#include <cmath>
#include <string>

#include "core/stopwatch.h"
#include "integrator/renderer.h"
#include "scene/default_scene.h"

namespace lueur::bench {
namespace {

using Json = nlohmann::ordered_json;

/// What a variant is compared on: one layer, or the weighted combination of the enabled passes.
struct Measure {
  const char* name;
  bool combined;
  Layer layer;
};

Image measure_image(const Film& film, const RenderSettings& settings, const Measure& m) {
  return m.combined ? combine_passes(film, settings.enabled, kReportWeights) : layer_average(film, m.layer);
}

struct Setup {
  const TracedScene& traced;
  Camera camera;
  ThreadPool& pool;
};

Film render_frames(const Setup& s, const RenderSettings& settings, int frames, std::FILE* log, const char* what) {
  Accumulation accumulation;
  accumulation.reset(settings);
  const Clock::time_point start = Clock::now();
  for (int f = 0; f < frames; ++f) render_frame(s.traced, s.camera, settings, accumulation, s.pool);
  Film film = std::move(accumulation.film);
  std::fprintf(log, "lueur-bench: reference %s: %d frames in %.1f s\n", what, frames, seconds_since(start));
  return film;
}

/// Renders frames until `seconds` have passed; records the RMSE of each measure at 1, 2, 4, ... frames and at the
/// end.
Json run_variant(const Setup& s, const RenderSettings& settings, const std::vector<Measure>& measures,
                 const std::vector<Image>& references, double seconds) {
  Accumulation accumulation;
  accumulation.reset(settings);
  const Film& film = accumulation.film;
  Json curve = Json::array();
  auto errors = [&] {
    Json e = Json::object();
    for (size_t m = 0; m < measures.size(); ++m)
      e[measures[m].name] = image_rmse(measure_image(film, settings, measures[m]), references[m]);
    return e;
  };
  // Time spent computing RMSE for the curve is not the variant's: it is taken out of the clock.
  const Clock::time_point start = Clock::now();
  Clock::duration paused{0};
  double elapsed = 0.0;
  for (uint64_t checkpoint = 1;;) {
    render_frame(s.traced, s.camera, settings, accumulation, s.pool);
    elapsed = std::chrono::duration<double>(Clock::now() - start - paused).count();
    const bool done = elapsed >= seconds;
    if (film.frames == checkpoint || done) {
      const Clock::time_point pause = Clock::now();
      curve.push_back(Json{{"frames", film.frames}, {"seconds", elapsed}, {"rmse", errors()}});
      if (film.frames == checkpoint) checkpoint *= 2;
      paused += Clock::now() - pause;
    }
    if (done) break;
  }
  Json v;
  v["frames"] = film.frames;
  v["seconds"] = elapsed;
  v["seconds_per_frame"] = elapsed / static_cast<double>(film.frames);
  v["rmse"] = curve.back()["rmse"];
  v["curve"] = curve;
  return v;
}

}  // namespace

Json run_convergence(const ConvergenceOptions& o, std::FILE* log) {
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  const auto traced = prepare_scene(std::move(scene));
  ThreadPool pool(o.threads);
  const Setup setup{*traced, make_camera(default_scene_camera(), o.width, o.height), pool};
  const std::string size = std::to_string(o.width) + "x" + std::to_string(o.height);
  Json results = Json::array();

  // Light strategies: L1 alone.
  RenderSettings l1;
  l1.width = o.width;
  l1.height = o.height;
  l1.enabled = {false, true, false, false};
  l1.seed = o.seed + 1000;
  l1.lights = LightStrategy::kArea;
  const std::vector<Measure> l1_measures = {{"l1", false, Layer::kL1}};
  {
    const Film reference = render_frames(setup, l1, o.reference_frames, log, "L1 (lights area, 16 rays)");
    const std::vector<Image> refs = {layer_average(reference, Layer::kL1)};
    for (int k = 0; k < static_cast<int>(kLightStrategyNames.size()); ++k) {
      RenderSettings s = l1;
      s.seed = o.seed;
      s.lights = static_cast<LightStrategy>(k);
      s.l1_rays = 1;
      Json v{{"scene", "default"},
             {"size", size},
             {"variant", "lights=" + std::string(kLightStrategyNames[k])},
             {"passes", "l1"},
             {"rays_per_pixel", 1}};
      v.update(run_variant(setup, s, l1_measures, refs, o.seconds));
      v["reference"] = Json{{"frames", o.reference_frames}, {"lights", "area"}, {"rays_per_pixel", l1.l1_rays}};
      std::fprintf(log, "lueur-bench: convergence %-16s %4d frames, %.3f s/frame, RMSE l1 %.5f\n",
                   v["variant"].get<std::string>().c_str(), v["frames"].get<int>(),
                   v["seconds_per_frame"].get<double>(), v["rmse"]["l1"].get<double>());
      results.push_back(v);
    }
  }

  // Reuse modes: the default passes.
  RenderSettings full;
  full.width = o.width;
  full.height = o.height;
  full.seed = o.seed + 1000;
  full.reuse = ReuseMode::kOff;
  const std::vector<Measure> full_measures = {{"image", true, Layer::kL1}, {"l2", false, Layer::kL2}};
  {
    const Film reference = render_frames(setup, full, o.reference_frames, log, "Le + L1 + L2 (reuse off)");
    const std::vector<Image> refs = {measure_image(reference, full, full_measures[0]),
                                     layer_average(reference, Layer::kL2)};
    for (int k = 0; k < static_cast<int>(kReuseModeNames.size()); ++k) {
      RenderSettings s = full;
      s.seed = o.seed;
      s.reuse = static_cast<ReuseMode>(k);
      Json v{{"scene", "default"},
             {"size", size},
             {"variant", "reuse=" + std::string(kReuseModeNames[k])},
             {"passes", "le,l1,l2"},
             {"rays_per_pixel", s.l1_rays}};
      v.update(run_variant(setup, s, full_measures, refs, o.seconds));
      v["reference"] = Json{{"frames", o.reference_frames}, {"reuse", "off"}, {"rays_per_pixel", full.l1_rays}};
      std::fprintf(log, "lueur-bench: convergence %-16s %4d frames, %.3f s/frame, RMSE image %.5f, l2 %.5f\n",
                   v["variant"].get<std::string>().c_str(), v["frames"].get<int>(),
                   v["seconds_per_frame"].get<double>(), v["rmse"]["image"].get<double>(),
                   v["rmse"]["l2"].get<double>());
      results.push_back(v);
    }
  }
  return results;
}

double image_mse(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    const double d = static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i]);
    sum += d * d;
  }
  return a.rgb.empty() ? 0.0 : sum / static_cast<double>(a.rgb.size());
}

double image_rmse(const Image& a, const Image& b) { return std::sqrt(image_mse(a, b)); }

TwoRenderReference reference_of_two(const Image& a, const Image& b) {
  TwoRenderReference r{a, image_mse(a, b) / 4.0};
  for (size_t i = 0; i < r.mean.rgb.size(); ++i) r.mean.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
  return r;
}

double image_relmse(const Image& image, const Image& reference) {
  double sum = 0.0;
  for (size_t i = 0; i < image.rgb.size(); ++i) {
    const double x = image.rgb[i], ref = reference.rgb[i];
    sum += (x - ref) * (x - ref) / (ref * ref + 0.01);
  }
  return image.rgb.empty() ? 0.0 : sum / static_cast<double>(image.rgb.size());
}

}  // namespace lueur::bench
