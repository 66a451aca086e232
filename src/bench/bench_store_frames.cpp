// L2's error by frames, per reuse mode (see bench_store_frames.h). Errors are mean squared errors over the pixels'
// channels, the two-render reference's own noise taken out (bench_convergence.h, reference_of_two).
#include "bench/bench_store_frames.h"

#include <chrono>
#include <fstream>
#include <iterator>
#include <string>

#include "bench/bench_convergence.h"
#include "core/atomic_file.h"
#include "image/image_output.h"
#include "integrator/renderer.h"

namespace lueur::bench {
namespace {

using Clock = std::chrono::steady_clock;
using Json = nlohmann::ordered_json;

struct Checkpoint {
  uint64_t frames = 0;
  double seconds = 0.0;  ///< the mode's render_frame time up to here
  double l2_mse = 0.0;   ///< the reference's noise taken out
};

struct Run {
  std::vector<Checkpoint> checkpoints;
  uint64_t bounce_hits = 0, from_screen = 0, from_store = 0;
  ServedSamples served;  ///< the samples of the cells that served bounce hits, over the run
  L1CacheStats store;
};

/// `frames` frames of `settings`; the L2 error at each power of two from `first_checkpoint` on (when `reference`).
Run render(const TracedScene& traced, const Camera& camera, const RenderSettings& settings, ThreadPool& pool,
           uint64_t frames, uint64_t first_checkpoint, const Image* reference, double reference_noise,
           Accumulation& into) {
  into.reset(settings);
  Run run;
  double seconds = 0.0;
  uint64_t next = first_checkpoint;
  for (uint64_t f = 0; f < frames; ++f) {
    const Clock::time_point start = Clock::now();
    const FrameResult r = render_frame(traced, camera, settings, into, pool);
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    run.bounce_hits += r.l2_bounce_hits;
    run.from_screen += r.l2_reused;
    run.from_store += r.l2_cached;
    run.served.add(r.served_samples);
    run.store = r.cache;
    if (reference && into.film.frames == next) {
      const double mse = image_mse(layer_average(into.film, Layer::kL2), *reference);
      run.checkpoints.push_back({next, seconds, mse - reference_noise});
      next *= 2;
    }
  }
  return run;
}

/// Reads `path` whole into `bytes`; false where it does not exist.
bool read_file_if_present(const std::string& path, std::string& bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

double share(uint64_t part, uint64_t whole) {
  return whole ? static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

}  // namespace

Json run_store_frames(std::vector<BenchScene>& scenes, const StoreFramesOptions& o, std::FILE* log) {
  Json results = Json::array();
  ThreadPool pool(o.threads);
  for (BenchScene& b : scenes) {
    if (b.name != "default" && b.name != "conference" && b.name != "room") continue;
    const auto traced = prepare_scene(b.scene);
    const Camera camera = make_camera(b.view, o.size, o.size);
    RenderSettings base;
    base.width = base.height = o.size;
    base.enabled = {};
    base.enabled[static_cast<size_t>(Pass::kL2)] = true;

    // The reference: two `off` renders with seeds of their own, averaged; their difference measures its noise.
    Accumulation scratch;
    RenderSettings reference_settings = base;
    reference_settings.reuse = ReuseMode::kOff;
    Image halves[2];
    const Clock::time_point reference_start = Clock::now();
    for (int h = 0; h < 2; ++h) {
      const std::string kept = o.reference_dir.empty()
                                   ? ""
                                   : o.reference_dir + "/" + b.name + "-" + std::to_string(o.size) + "-" +
                                         std::to_string(o.reference_frames) + "-" + std::to_string(h) + ".pfm";
      std::string bytes;
      if (!kept.empty() && read_file_if_present(kept, bytes)) {
        halves[h] = decode_pfm(bytes);
        continue;
      }
      reference_settings.seed = 1000 + static_cast<uint64_t>(h);
      render(*traced, camera, reference_settings, pool, o.reference_frames, 0, nullptr, 0.0, scratch);
      halves[h] = layer_average(scratch.film, Layer::kL2);
      if (!kept.empty()) write_file_atomically(kept, encode_pfm(halves[h]));
    }
    const TwoRenderReference two = reference_of_two(halves[0], halves[1]);
    const Image& reference = two.mean;
    const double reference_noise = two.noise;
    std::fprintf(log, "lueur-bench: store-frames %s: reference 2 x %llu frames (reuse off) in %.0f s, noise %.3g\n",
                 b.name.c_str(), static_cast<unsigned long long>(o.reference_frames),
                 std::chrono::duration<double>(Clock::now() - reference_start).count(), reference_noise);

    for (const ReuseMode mode : o.modes) {
      RenderSettings s = base;
      s.reuse = mode;
      s.seed = 1;
      const Run run =
          render(*traced, camera, s, pool, o.frames, o.first_checkpoint, &reference, reference_noise, scratch);
      const std::string name(kReuseModeNames[static_cast<size_t>(mode)]);
      Json points = Json::array();
      std::string line;
      for (size_t c = 0; c < run.checkpoints.size(); ++c) {
        const Checkpoint& p = run.checkpoints[c];
        Json point{{"frames", p.frames}, {"seconds", p.seconds}, {"l2_mse", p.l2_mse}};
        // The slope over the octave that ends here: log2 of the error's ratio (-1: as 1 / frames).
        if (c > 0 && p.l2_mse > 0.0 && run.checkpoints[c - 1].l2_mse > 0.0)
          point["octave_slope"] = std::log2(p.l2_mse / run.checkpoints[c - 1].l2_mse);
        points.push_back(point);
        char text[64];
        std::snprintf(text, sizeof text, " %.3g", p.l2_mse);
        line += text;
      }
      const bool store = uses_cache(mode);
      results.push_back(Json{{"scene", b.name},
                             {"size", o.size},
                             {"reuse", name},
                             {"reference_frames", 2 * o.reference_frames},
                             {"reference_noise", reference_noise},
                             {"checkpoints", points},
                             {"share_from_screen", share(run.from_screen, run.bounce_hits)},
                             {"share_from_store", share(run.from_store, run.bounce_hits)},
                             {"served_cell_samples_median", store ? Json(run.served.percentile(0.5)) : Json(nullptr)},
                             {"served_cell_samples_p10", store ? Json(run.served.percentile(0.1)) : Json(nullptr)},
                             {"cache_cells", run.store.cells}});
      std::fprintf(log, "lueur-bench: store-frames %-10s %-13s %.1f s; L2 MSE at %llu, x2, ...:%s", b.name.c_str(),
                   name.c_str(), run.checkpoints.empty() ? 0.0 : run.checkpoints.back().seconds,
                   static_cast<unsigned long long>(o.first_checkpoint), line.c_str());
      if (store)
        std::fprintf(log, "; served by cells of median %u, 10th percentile %u samples", run.served.percentile(0.5),
                     run.served.percentile(0.1));
      std::fprintf(log, "\n");
      std::fflush(log);
    }
  }
  return results;
}

}  // namespace lueur::bench
