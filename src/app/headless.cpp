// Headless rendering: progress on stderr while it runs, a summary at the end, the image written atomically.
#include "app/headless.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/displayed_image.h"
#include "app/scene_source.h"
#include "app/split_output.h"
#include "core/atomic_file.h"
#include "core/memory_budget.h"
#include "image/image_output.h"
#include "render/noise_estimate.h"
#include "render/render_memory.h"
#include "render/renderer.h"
#include "scene/obj_loader.h"
#include "settings/compare.h"
#include "ui/headless_screenshot.h"
#include "ui/panel.h"

namespace lueur {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// Refuses an output that could never be written before spending minutes rendering it.
void check_output_path(const std::string& path) {
  if (!is_supported_image_path(path))
    throw IoError("cannot write '" + path + "': unknown image format (use .png, .pfm or .exr)");
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError("cannot write '" + path + "': it is a directory");
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) throw IoError("cannot write '" + path + "': no directory '" + dir.string() + "'");
  if (::access(dir.c_str(), W_OK) != 0) throw IoError("cannot write '" + path + "': directory is not writable");
}

/// Refuses an image whose buffers the machine cannot hold, before anything is loaded or allocated; returns what
/// is left of the budget for the scene.
MemoryBudget reserve_render_memory(const RenderSettings& settings, const RenderSettings* right) {
  const MemoryBudget budget = available_memory();
  const uint64_t needed = render_memory_bytes(settings) + (right ? render_memory_bytes(*right) : 0);
  const std::string size = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  if (needed > budget.bytes)
    throw UsageError("--size " + size + ": rendering needs about " + format_bytes(needed) +
                     " of memory, more than the " + format_bytes(budget.bytes) + " available (" + budget.source + ")");
  return {budget.bytes - needed, budget.source + ", less " + format_bytes(needed) + " for the " + size + " image"};
}

struct RunFigures {
  double seconds = 0.0;
  uint64_t rays = 0;
  double l2_seconds = 0.0;
  uint64_t bounce_hits = 0, reused = 0, cached = 0;
  L1CacheStats cache;
  std::vector<NoisePoint> noise_history;           ///< the estimate at each power of two of the frames (for --ui)
  double left_seconds = 0.0, right_seconds = 0.0;  ///< an A/B split's tracing time per side
};

/// The PNG through the display shaders of an off-screen EGL or OSMesa context, with the panel if asked, split with
/// `right` if given.
void write_gl_screenshot(const AppOptions& options, const Settings& described, const Film& film,
                         const TracedScene& traced, const RunFigures& figures, const Film* right) {
  PanelModel panel;
  if (options.ui) {
    panel.settings = options.settings;
    panel.paused = true;
    panel.stats.frames = film.frames;
    panel.stats.seconds = figures.seconds;
    // Headless frames are not timed one by one: the panel shows their mean.
    panel.stats.last_frame_seconds = film.frames > 0 ? figures.seconds / static_cast<double>(film.frames) : 0.0;
    panel.stats.rays = figures.rays;
    panel.stats.l2_seconds = figures.l2_seconds;
    panel.stats.l2_bounce_hits = figures.bounce_hits;
    panel.stats.l2_reused = figures.reused;
    panel.stats.l2_cached = figures.cached;
    panel.stats.cache = figures.cache;
    panel.noise = estimate_film_noise(film, options.settings.render.enabled, options.settings.weights,
                                      options.settings.render.sampler);
    panel.noise_history = figures.noise_history;
    record_noise(panel, panel.noise, figures.seconds);
    if (right) {
      const Settings right_settings = *compared_settings(options.settings);
      panel.comparing = true;
      panel.stats.seconds = figures.left_seconds;
      panel.right_noise = estimate_image_noise(*right, right_settings.render.enabled, right_settings.weights,
                                               right_settings.render.sampler);
      panel.right_stats.frames = right->frames;
      panel.right_stats.seconds = figures.right_seconds;
    }
    panel.film_width = film.width;
    panel.film_height = film.height;
    describe_scene(panel, traced);
  }
  Screenshot shot;
  try {
    shot = render_headless_screenshot(options.gl, film, options.settings, options.ui ? &panel : nullptr, right);
  } catch (const std::runtime_error& e) {
    throw IoError(std::string("--gl ") + std::string(enum_name(kHeadlessGlNames, options.gl)) + ": " + e.what());
  }
  std::fprintf(stderr, "lueur: display path: %s\n", shot.context.c_str());
  write_file_atomically(options.out_path, encode_png_rgb8(shot.rgb, shot.width, shot.height,
                                                          describe_options(options.scene_path, described)));
}

/// One side of an A/B split: its image's estimated relMSE, its tracing time, and their product, the error it would
/// have after one second of tracing if the error falls as 1/time (lower is better).
void print_side(const std::string& name, const Film& film, const Settings& settings, double seconds) {
  const NoiseEstimate e =
      estimate_image_noise(film, settings.render.enabled, settings.weights, settings.render.sampler);
  if (!e.known) {
    std::fprintf(stderr, "lueur: %s: %.2f s of tracing, estimated relMSE unknown\n", name.c_str(), seconds);
    return;
  }
  std::fprintf(stderr, "lueur: %s: %.2f s of tracing, estimated relMSE %.4g, relMSE x seconds %.4g\n", name.c_str(),
               seconds, e.rel_mse, e.rel_mse * seconds);
}

/// The estimated noise of each rendered pass, then the combined image's as a plain "estimated relMSE X" last.
void print_noise_summary(const Film& film, const RenderSettings& settings,
                         const std::array<float, kPassCount>& weights) {
  const FilmNoise noise = estimate_film_noise(film, settings.enabled, weights, settings.sampler);
  const auto print = [&](const std::string& what, const NoiseEstimate& e) {
    if (e.known)
      std::fprintf(stderr, "lueur: %s: estimated relMSE %.4g (variance falls as frames^-%.2f)\n", what.c_str(),
                   e.rel_mse, e.exponent);
    else
      std::fprintf(stderr, "lueur: %s: estimated relMSE unknown (it needs %llu frames)\n", what.c_str(),
                   static_cast<unsigned long long>(frames_before_noise_estimate(settings.sampler)));
  };
  for (int p = 0; p < kPassCount; ++p)
    if (settings.enabled[static_cast<size_t>(p)])
      print(std::string(kPassNames[static_cast<size_t>(p)]) + " pass", noise.passes[static_cast<size_t>(p)]);
  print("image", noise.image);
}

}  // namespace

int run_headless(const AppOptions& options) {
  check_output_path(options.out_path);
  const RenderSettings& settings = options.settings.render;
  const int frames = options.settings.frames;
  // An A/B split renders a second film with the compared setting changed, frame for frame with the first.
  const std::optional<Settings> right = compared_settings(options.settings);
  const MemoryBudget scene_memory = reserve_render_memory(settings, right ? &right->render : nullptr);
  const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
  const OpenedScene opened = open_scene(options.scene_path, scene_options_of(options.settings), aspect, scene_memory);
  for (const std::string& w : opened.warnings) std::fprintf(stderr, "lueur: warning: %s\n", w.c_str());
  if (!options.settings.camera)
    for (const std::string& note : opened.notes) std::fprintf(stderr, "lueur: %s\n", note.c_str());

  const Camera camera = make_camera(camera_of(options.settings, opened.default_view), settings.width, settings.height);

  Film film;
  film.reset(settings);
  const std::optional<Layer> layer = options.settings.layer;
  if (layer && !film.has(*layer))
    throw UsageError("--view " + std::string(enum_name(kLayerNames, *layer)) +
                     ": that layer is not rendered with these --passes/--reuse settings");
  Film right_film;
  if (right) {
    right_film.reset(right->render);
    if (layer && !right_film.has(*layer))
      throw UsageError("--view " + std::string(enum_name(kLayerNames, *layer)) +
                       ": that layer is not rendered on the right side of --compare " + options.settings.compare);
  }
  ThreadPool pool(options.threads);
  const TracedScene& traced = *opened.traced;
  std::string textures;
  if (!traced.scene.textures.empty())
    textures = ", " + std::to_string(traced.scene.textures.size()) +
               (traced.scene.textures.size() == 1 ? " texture (" : " textures (") +
               format_bytes(traced.scene.texture_bytes()) + (traced.scene.has_cutouts() ? ", with cutouts)" : ")");
  std::fprintf(stderr, "lueur: %s, %zu triangles, %zu emitters%s, %dx%d, %d frames, %d threads, accel %s\n",
               traced.scene.name.c_str(), traced.scene.triangles.size(), traced.lights.size(), textures.c_str(),
               settings.width, settings.height, frames, pool.thread_count(),
               std::string(enum_name(kAccelKindNames, options.settings.accel)).c_str());

  const Clock::time_point start = Clock::now();
  Clock::time_point last_progress = start;
  uint64_t rays = 0, bounce_hits = 0, reused = 0, cached = 0, dropped = 0;
  L1CacheStats cache;
  std::vector<NoisePoint> noise_history;
  double l2_seconds = 0.0;
  const bool tty = ::isatty(STDERR_FILENO);
  const double time_limit = options.settings.time_limit;
  const double target_noise = options.settings.target_noise;
  bool stopped_by_noise = false;
  RunningNoiseEstimate running_noise;              // for the target, remade at powers of two of the frames
  double left_seconds = 0.0, right_seconds = 0.0;  // each side's tracing time
  int done = 0;
  for (int f = 0; f < frames; ++f) {
    const Clock::time_point frame_start = Clock::now();
    const FrameResult frame = render_frame(traced, camera, settings, film, pool);
    left_seconds += seconds_since(frame_start);
    if (right) {
      const Clock::time_point right_start = Clock::now();
      rays += render_frame(traced, camera, right->render, right_film, pool).rays;
      right_seconds += seconds_since(right_start);
    }
    rays += frame.rays;
    bounce_hits += frame.l2_bounce_hits;
    reused += frame.l2_reused;
    cached += frame.l2_cached;
    cache = frame.cache;
    dropped += frame.dropped_samples;
    l2_seconds += frame.l2_seconds;
    const double elapsed = seconds_since(start);
    done = f + 1;
    const bool out_of_time = time_limit > 0.0 && elapsed >= time_limit;
    // The panel's plot in a --ui screenshot: the estimate at every power of two of the frames.
    if (options.ui && options.gl != HeadlessGl::kNone && (film.frames & (film.frames - 1)) == 0) {
      PanelModel history;
      history.noise_history = std::move(noise_history);
      record_noise(history, estimate_film_noise(film, settings.enabled, options.settings.weights, settings.sampler),
                   elapsed);
      noise_history = std::move(history.noise_history);
    }
    bool quiet_enough = false;
    if (target_noise > 0.0) {
      const NoiseEstimate& noise =
          running_noise.update(film, settings.enabled, options.settings.weights, settings.sampler).image;
      // Confirmed by a full estimate, so that the summary's figure is below the target too.
      quiet_enough = noise.known && noise.rel_mse < target_noise &&
                     estimate_image_noise(film, settings.enabled, options.settings.weights, settings.sampler).rel_mse <
                         target_noise;
    }
    if (done == frames || out_of_time || quiet_enough ||
        std::chrono::duration<double>(Clock::now() - last_progress).count() > 0.5) {
      last_progress = Clock::now();
      const double left = elapsed / (f + 1) * (frames - f - 1);
      std::fprintf(stderr, "%slueur: frame %d/%d, %.1f s elapsed, about %.1f s left%s", tty ? "\r" : "", f + 1, frames,
                   elapsed, left, tty ? "   " : "\n");
    }
    if (quiet_enough) {
      std::fprintf(stderr, "%slueur: target noise %g reached after %d frames, %.2f s\n", tty ? "\n" : "", target_noise,
                   done, elapsed);
      stopped_by_noise = true;
      break;
    }
    if (out_of_time) break;
  }
  const double elapsed = seconds_since(start);
  if (tty) std::fprintf(stderr, "\n");
  if (done < frames && !stopped_by_noise)
    std::fprintf(stderr, "lueur: time limit of %g s reached after %d of %d frames\n", time_limit, done, frames);
  if (target_noise > 0.0 && !stopped_by_noise)
    std::fprintf(stderr, "lueur: target noise %g not reached in %d frames (raise --frames)\n", target_noise, done);
  // The image holds the settings that render it again: the frames done, not the time they took here.
  Settings described = options.settings;
  described.frames = done;
  described.time_limit = 0.0f;
  described.target_noise = 0.0f;

  if (dropped > 0)
    std::fprintf(stderr,
                 "lueur: warning: %llu pixel samples were not finite or would overflow the image and were dropped "
                 "(a scene of extreme scale or emission)\n",
                 static_cast<unsigned long long>(dropped));
  if (options.gl != HeadlessGl::kNone) {
    write_gl_screenshot(
        options, described, film, traced,
        {elapsed, rays, l2_seconds, bounce_hits, reused, cached, cache, noise_history, left_seconds, right_seconds},
        right ? &right_film : nullptr);
  } else if (right) {
    write_split_image(options.out_path, film, right_film, options.settings,
                      describe_options(options.scene_path, described));
  } else {
    // The EXR holds every rendered layer; PNG and PFM show the combined image or the chosen --view.
    write_image(options.out_path, displayed_image(film, options.settings), film_layer_images(film),
                displayed_transform(options.settings), describe_options(options.scene_path, described));
  }

  std::fprintf(stderr, "lueur: %d frames in %.2f s, %.1f M rays traced (%.2f Mrays/s)\n", done, elapsed,
               static_cast<double>(rays) * 1e-6, elapsed > 0.0 ? static_cast<double>(rays) * 1e-6 / elapsed : 0.0);
  if (settings.pass_enabled(Pass::kL2))
    std::fprintf(stderr, "lueur: L2 took %.2f s; %.1f%% of its %.1f M bounce hits reused L1 (--reuse %s)\n", l2_seconds,
                 bounce_hits ? 100.0 * static_cast<double>(reused) / static_cast<double>(bounce_hits) : 0.0,
                 static_cast<double>(bounce_hits) * 1e-6,
                 std::string(enum_name(kReuseModeNames, settings.reuse)).c_str());
  if (settings.pass_enabled(Pass::kL2) && uses_cache(settings.reuse)) {
    const auto share = [&](uint64_t n) {
      return bounce_hits ? 100.0 * static_cast<double>(n) / static_cast<double>(bounce_hits) : 0.0;
    };
    std::fprintf(stderr,
                 "lueur: L1 store: %.1f%% of the bounce hits took L1 from it, %.1f%% recomputed it; %llu cells, %.1f "
                 "MiB of %d MiB%s\n",
                 share(cached), share(bounce_hits - reused - cached), static_cast<unsigned long long>(cache.cells),
                 static_cast<double>(cache.bytes) / (1 << 20), settings.cache_mb,
                 cache.full ? " (full: new cells refused)" : "");
  }
  if (right) {
    print_side("left (as set)", film, options.settings, left_seconds);
    print_side("right (" + options.settings.compare + ")", right_film, *right, right_seconds);
  }
  print_noise_summary(film, settings, options.settings.weights);
  std::printf("%s\n", options.out_path.c_str());
  return 0;
}

}  // namespace lueur
