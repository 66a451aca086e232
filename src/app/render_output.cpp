// The parts of a headless render that do not depend on who traces the frames.
#include "app/render_output.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/displayed_image.h"
#include "app/interrupt.h"
#include "app/load_progress_line.h"
#include "app/split_output.h"
#include "core/atomic_file.h"
#include "core/regular_file.h"
#include "core/stopwatch.h"
#include "film/noise_estimate.h"
#include "image/image_output.h"
#include "runtime/render_memory.h"
#include "scene/obj_loader.h"
#include "settings/compare.h"
#include "settings/setting_table.h"
#include "ui/headless_screenshot.h"

namespace lueur {
namespace {

/// The settings written into the image: those given, with the frames done rather than the time they took here.
Settings described_settings(const Settings& given, uint64_t frames_done) {
  Settings described = given;
  described.frames = static_cast<int>(frames_done);
  described.time_limit = 0.0f;
  described.target_noise = 0.0f;
  described.watch = true;  // the window's, not the image's
  return described;
}

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
    panel.stats.rays = figures.tally.rays;
    panel.stats.l2_seconds = figures.tally.l2_seconds;
    panel.stats.l2_bounce_hits = figures.tally.bounce_hits;
    panel.stats.l2_reused = figures.tally.reused;
    panel.stats.l2_cached = figures.tally.cached;
    panel.stats.ln_lookups = figures.tally.ln_lookups;
    panel.stats.ln_reused = figures.tally.ln_reused;
    panel.stats.ln_cached = figures.tally.ln_cached;
    panel.stats.ln_paths = figures.tally.ln_paths;
    panel.stats.ln_ended = figures.tally.ln_ended;
    panel.stats.served = figures.tally.served;
    panel.stats.cache = figures.cache;
    panel.noise = estimate_film_noise(film, options.settings.render.enabled, options.settings.weights,
                                      options.settings.render.sampler);
    panel.noise_history = figures.noise_history;
    record_noise(panel, panel.noise, figures.seconds);
    if (right) {
      const Settings right_settings = *compared_settings(options.settings);
      panel.comparing = true;
      panel.stats.seconds = figures.tally.left_seconds;
      panel.right_noise = estimate_image_noise(*right, right_settings.render.enabled, right_settings.weights,
                                               right_settings.render.sampler);
      panel.right_stats.frames = right->frames;
      panel.right_stats.seconds = figures.tally.right_seconds;
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

void FrameTally::add(const FrameTally& other) {
  rays += other.rays;
  bounce_hits += other.bounce_hits;
  reused += other.reused;
  cached += other.cached;
  ln_lookups += other.ln_lookups;
  ln_reused += other.ln_reused;
  ln_cached += other.ln_cached;
  ln_paths += other.ln_paths;
  ln_ended += other.ln_ended;
  served.add(other.served);
  dropped += other.dropped;
  l2_seconds += other.l2_seconds;
  left_seconds += other.left_seconds;
  right_seconds += other.right_seconds;
}

FrameResult render_frame_pair(const TracedScene& traced, const Camera& camera, const RenderSettings& left_settings,
                              Accumulation& left, const RenderSettings* right_settings, Accumulation* right,
                              ThreadPool& pool, FrameTally& tally) {
  const Clock::time_point left_start = Clock::now();
  const FrameResult frame = render_frame(traced, camera, left_settings, left, pool);
  tally.left_seconds += seconds_since(left_start);
  if (right) {
    const Clock::time_point right_start = Clock::now();
    const FrameResult right_frame = render_frame(traced, camera, *right_settings, *right, pool);
    tally.rays += right_frame.rays;
    tally.dropped += right_frame.dropped_samples;
    tally.right_seconds += seconds_since(right_start);
  }
  tally.rays += frame.rays;
  tally.bounce_hits += frame.l2_bounce_hits;
  tally.reused += frame.l2_reused;
  tally.cached += frame.l2_cached;
  tally.ln_lookups += frame.ln_lookups;
  tally.ln_reused += frame.ln_reused;
  tally.ln_cached += frame.ln_cached;
  tally.ln_paths += frame.ln_paths;
  tally.ln_ended += frame.ln_ended;
  tally.served.add(frame.served_samples);
  tally.dropped += frame.dropped_samples;
  tally.l2_seconds += frame.l2_seconds;
  return frame;
}

void check_output_path(const std::string& path) {
  if (!is_supported_image_path(path))
    throw IoError("cannot write '" + path + "': unknown image format (use .png, .pfm or .exr)");
  check_writable_path(path);
}

void check_writable_path(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError("cannot write '" + path + "': it is a directory");
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec)) throw IoError("cannot write '" + path + "': no directory '" + dir.string() + "'");
  if (::access(dir.c_str(), W_OK) != 0) throw IoError("cannot write '" + path + "': directory is not writable");
}

void refuse_repeating_samples(const RenderSettings& settings, int frames, const std::string& side) {
  const uint64_t most = frames_before_samples_repeat(settings);
  if (static_cast<uint64_t>(std::max(frames, 0)) <= most) return;
  throw UsageError("--frames " + std::to_string(frames) + ": at these ray counts" + side +
                   " each pixel's sample sequence (2^32 samples) starts over after " + std::to_string(most) +
                   " frames, and further frames would repeat earlier ones: ask for at most " + std::to_string(most) +
                   " frames, or fewer rays per frame (--l2-rays, --l1-rays, --recompute-ratio)");
}

MemoryBudget reserve_render_memory(const RenderSettings& settings, const RenderSettings* right) {
  const MemoryBudget budget = available_memory();
  const uint64_t needed = render_memory_bytes(settings) + (right ? render_memory_bytes(*right) : 0);
  const std::string size = std::to_string(settings.width) + "x" + std::to_string(settings.height);
  if (needed > budget.bytes)
    throw UsageError("--size " + size + ": rendering needs about " + format_bytes(needed) +
                     " of memory, more than the " + format_bytes(budget.bytes) + " available (" + budget.source + ")");
  return {budget.bytes - needed, budget.source + ", less " + format_bytes(needed) + " for the " + size + " image"};
}

RenderJob prepare_render_job(const AppOptions& options, bool writes_output) {
  if (writes_output) check_output_path(options.out_path);
  RenderJob job;
  const RenderSettings& settings = options.settings.render;
  // An A/B split renders a second film with the compared setting changed, frame for frame with the first.
  job.right = compared_settings(options.settings);
  refuse_repeating_samples(settings, options.settings.frames, "");
  if (job.right) refuse_repeating_samples(job.right->render, options.settings.frames, " (the right side of --compare)");
  const MemoryBudget scene_memory = reserve_render_memory(settings, job.right ? &job.right->render : nullptr);
  const float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
  const Clock::time_point load_start = Clock::now();
  SceneOptions scene_options = scene_options_of(options.settings);
  scene_options.threads = static_cast<unsigned>(std::max(options.threads, 0));
  {
    LoadProgressLine line(options.scene_path.empty() ? std::string("the default scene") : options.scene_path,
                          writes_output && ::isatty(STDERR_FILENO));
    job.opened = open_scene(options.scene_path, scene_options, aspect, scene_memory, line.callback());
  }
  job.load_seconds = seconds_since(load_start);
  if (writes_output)
    for (const std::string& w : job.opened.warnings) std::fprintf(stderr, "lueur: warning: %s\n", w.c_str());
  if (writes_output && !options.settings.camera)
    for (const std::string& note : job.opened.notes) std::fprintf(stderr, "lueur: %s\n", note.c_str());
  // Allowed (the panel can uncheck every pass too), but a black file with no word of why looks like a bug.
  if (writes_output && std::none_of(settings.enabled.begin(), settings.enabled.end(), [](bool on) { return on; }))
    std::fprintf(stderr, "lueur: warning: --passes names no pass: nothing is rendered and the image is black\n");
  job.camera = make_camera(camera_of(options.settings, job.opened.default_view), settings.width, settings.height);

  job.left.reset(settings);
  const std::optional<Layer> layer = options.settings.layer;
  if (layer && !job.left.film.has(*layer))
    throw UsageError("--view " + std::string(enum_name(kLayerNames, *layer)) +
                     ": that layer is not rendered with these --passes/--reuse settings");
  if (job.right) {
    job.right_side.reset(job.right->render);
    if (layer && !job.right_side.film.has(*layer))
      throw UsageError("--view " + std::string(enum_name(kLayerNames, *layer)) +
                       ": that layer is not rendered on the right side of --compare " + options.settings.compare);
  }
  return job;
}

void print_render_header(const AppOptions& options, const RenderJob& job, const std::string& workers) {
  const TracedScene& traced = *job.opened.traced;
  const RenderSettings& settings = options.settings.render;
  std::string textures;
  if (!traced.scene.textures.empty())
    textures = ", " + std::to_string(traced.scene.textures.size()) +
               (traced.scene.textures.size() == 1 ? " texture (" : " textures (") +
               format_bytes(traced.scene.texture_bytes()) + (traced.scene.has_cutouts() ? ", with cutouts)" : ")");
  std::fprintf(stderr, "lueur: %s, %zu triangles, %zu emitters%s, %dx%d, %d frames, %s, accel %s, loaded in %.3f s\n",
               traced.scene.name.c_str(), traced.scene.triangles.size(), traced.lights.size(), textures.c_str(),
               settings.width, settings.height, options.settings.frames, workers.c_str(),
               std::string(enum_name(kAccelKindNames, options.settings.accel)).c_str(), job.load_seconds);
  if (!job.opened.stage_times.empty())
    std::fprintf(stderr, "%s\n",
                 load_summary(describe_stage_times(job.opened.stage_times), traced.scene.triangles.size()).c_str());
}

void record_noise_history(const AppOptions& options, const Film& film, double elapsed, RunFigures& figures) {
  if (!options.ui || options.gl == HeadlessGl::kNone || !is_power_of_two(film.frames)) return;
  const RenderSettings& settings = options.settings.render;
  PanelModel history;
  history.noise_history = std::move(figures.noise_history);
  record_noise(history, estimate_film_noise(film, settings.enabled, options.settings.weights, settings.sampler),
               elapsed);
  figures.noise_history = std::move(history.noise_history);
}

void write_render_output(const AppOptions& options, const Film& film, const Film* right, const TracedScene& traced,
                         const RunFigures& figures) {
  const Settings described = described_settings(options.settings, film.frames);
  if (options.gl != HeadlessGl::kNone) {
    write_gl_screenshot(options, described, film, traced, figures, right);
  } else if (right) {
    write_split_image(options.out_path, film, *right, options.settings,
                      describe_options(options.scene_path, described));
  } else {
    // The EXR holds every rendered layer; PNG and PFM show the combined image or the chosen --view.
    write_image(options.out_path, displayed_image(film, options.settings), film_layer_images(film),
                displayed_transform(options.settings), describe_options(options.scene_path, described));
  }
}

std::string state_path_of(const std::string& out_path) { return out_path + ".lueur-state"; }

RenderIdentity render_identity(const AppOptions& options, const TracedScene& traced) {
  RenderIdentity identity;
  for (const SettingInfo& info : setting_infos()) {
    if (info.effect < SettingEffect::kRestart) continue;
    identity.push_back(info.option() + " " + setting_text(options.settings, info.name).value_or("(unset)"));
  }
  identity.push_back("the scene '" + (options.scene_path.empty() ? std::string("(default)") : options.scene_path) +
                     "' of " + std::to_string(traced.scene.triangles.size()) + " triangles");
  return identity;
}

void write_checkpoint(const AppOptions& options, const Accumulation& left, const Accumulation* right,
                      const TracedScene& traced, const RunFigures& figures) {
  std::vector<const Accumulation*> sides{&left};
  if (right) sides.push_back(right);
  write_render_output(options, left.film, right ? &right->film : nullptr, traced, figures);
  write_file_atomically(state_path_of(options.out_path), encode_resume_state(render_identity(options, traced), sides));
}

void finish_render(const AppOptions& options, const Accumulation& left, const Accumulation* right,
                   const TracedScene& traced, const RunFigures& figures, bool out_of_time, bool stopped_by_noise,
                   int interrupted_by) {
  const Film& film = left.film;
  if (interrupted_by != 0)
    std::fprintf(stderr,
                 "lueur: %s: stopped after %llu of %d frames; writing them%s (a second one ends lueur at once)\n",
                 signal_name(interrupted_by), static_cast<unsigned long long>(film.frames), options.settings.frames,
                 options.checkpoint_seconds > 0.0 ? ", and the state that --resume goes on from" : "");
  if (out_of_time && !stopped_by_noise)
    std::fprintf(stderr, "lueur: time limit of %g s reached after %llu of %d frames\n", options.settings.time_limit,
                 static_cast<unsigned long long>(film.frames), options.settings.frames);
  if (options.settings.target_noise > 0.0 && !stopped_by_noise && interrupted_by == 0)
    std::fprintf(stderr, "lueur: target noise %g not reached in %llu frames (raise --frames)\n",
                 options.settings.target_noise, static_cast<unsigned long long>(film.frames));
  if (options.checkpoint_seconds > 0.0)
    write_checkpoint(options, left, right, traced, figures);
  else
    write_render_output(options, film, right ? &right->film : nullptr, traced, figures);
}

void resume_render(const AppOptions& options, const TracedScene& traced, const std::vector<Accumulation*>& sides) {
  const std::string& path = options.resume_path;
  // A state no larger than the memory there is: its film was checked against that budget when it was rendered,
  // and /dev/zero or a FIFO named by mistake is refused before it fills memory or blocks.
  std::string bytes;
  try {
    bytes = read_regular_file(path, available_memory().bytes);
  } catch (const FileReadError& e) {
    throw UsageError(std::string("--resume: ") + e.what());
  }
  try {
    decode_resume_state(bytes, render_identity(options, traced), sides);
  } catch (const std::runtime_error& e) {
    throw UsageError("--resume '" + path + "': " + e.what());
  }
  if (sides.front()->film.frames > static_cast<uint64_t>(options.settings.frames))
    throw UsageError("--resume '" + path + "': it already holds " + std::to_string(sides.front()->film.frames) +
                     " frames, more than --frames " + std::to_string(options.settings.frames));
}

void print_run_summary(const AppOptions& options, const Film& film, const Film* right, const RunFigures& figures) {
  const RenderSettings& settings = options.settings.render;
  const double elapsed = figures.seconds;
  if (figures.tally.dropped > 0)
    std::fprintf(stderr,
                 "lueur: warning: %llu pixel samples were not finite or too large for the image and were dropped "
                 "(a scene of extreme scale or emission)\n",
                 static_cast<unsigned long long>(figures.tally.dropped));
  std::fprintf(stderr, "lueur: %llu frames in %.2f s, %.1f M rays traced (%.2f Mrays/s)\n",
               static_cast<unsigned long long>(film.frames), elapsed, static_cast<double>(figures.tally.rays) * 1e-6,
               elapsed > 0.0 ? static_cast<double>(figures.tally.rays) * 1e-6 / elapsed : 0.0);
  const uint64_t bounce_hits = figures.tally.bounce_hits;
  if (settings.pass_enabled(Pass::kL2))
    std::fprintf(
        stderr, "lueur: L2 took %.2f s; %.1f%% of its %.1f M bounce hits reused L1 (--reuse %s)\n",
        figures.tally.l2_seconds,
        bounce_hits ? 100.0 * static_cast<double>(figures.tally.reused) / static_cast<double>(bounce_hits) : 0.0,
        static_cast<double>(bounce_hits) * 1e-6, std::string(enum_name(kReuseModeNames, settings.reuse)).c_str());
  if (settings.pass_enabled(Pass::kL2) && uses_cache(settings.reuse)) {
    const auto share = [&](uint64_t n) {
      return bounce_hits ? 100.0 * static_cast<double>(n) / static_cast<double>(bounce_hits) : 0.0;
    };
    std::fprintf(stderr,
                 "lueur: L1 store: %.1f%% of the bounce hits took L1 from it, %.1f%% recomputed it; %llu cells, %.1f "
                 "MiB of %d MiB%s\n",
                 share(figures.tally.cached), share(bounce_hits - figures.tally.reused - figures.tally.cached),
                 static_cast<unsigned long long>(figures.cache.cells),
                 static_cast<double>(figures.cache.bytes) / (1 << 20), settings.cache_mb,
                 figures.cache.full ? " (full: new cells refused)" : "");
    if (figures.tally.served.total > 0)
      std::fprintf(stderr, "lueur: L1 store: the cells that served held %u samples (median), %u (10th percentile)\n",
                   figures.tally.served.percentile(0.5), figures.tally.served.percentile(0.1));
  }
  if (settings.pass_enabled(Pass::kLn) && figures.tally.ln_lookups > 0) {
    const auto share = [&](uint64_t n) {
      return 100.0 * static_cast<double>(n) / static_cast<double>(figures.tally.ln_lookups);
    };
    std::fprintf(stderr,
                 "lueur: ln: %.1f M vertices past the first bounce needed L1: %.1f%% from the screen, %.1f%% from "
                 "the L1 store, %.1f%% traced\n",
                 static_cast<double>(figures.tally.ln_lookups) * 1e-6, share(figures.tally.ln_reused),
                 share(figures.tally.ln_cached),
                 share(figures.tally.ln_lookups - figures.tally.ln_reused - figures.tally.ln_cached));
    if (figures.tally.ln_ended > 0)
      std::fprintf(stderr,
                   "lueur: ln: %.1f%% of its paths took their further light from the L1 store and ended there\n",
                   100.0 * static_cast<double>(figures.tally.ln_ended) / static_cast<double>(figures.tally.ln_paths));
  }
  if (right) {
    print_side("left (as set)", film, options.settings, figures.tally.left_seconds);
    print_side("right (" + options.settings.compare + ")", *right, *compared_settings(options.settings),
               figures.tally.right_seconds);
  }
  print_noise_summary(film, settings, options.settings.weights);
}

}  // namespace lueur
