// Headless rendering in one process: progress on stderr while it runs, the image (and, with --checkpoint, the
// resume state) written atomically, a summary at the end.
#include "app/headless.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "app/interrupt.h"
#include "app/render_output.h"
#include "app/scene_source.h"
#include "core/stopwatch.h"
#include "film/noise_estimate.h"
#include "integrator/renderer.h"
#include "settings/compare.h"

namespace lueur {

int run_headless(const AppOptions& options) {
  RenderJob job = prepare_render_job(options);
  const RenderSettings& settings = options.settings.render;
  const int frames = options.settings.frames;
  const std::optional<Settings>& right = job.right;
  Film& film = job.left.film;
  Accumulation* right_side = right ? &job.right_side : nullptr;
  const Camera& camera = job.camera;
  ThreadPool pool(options.threads);
  const TracedScene& traced = *job.opened.traced;
  if (!options.resume_path.empty()) {
    resume_render(options, traced, job.sides());
    std::fprintf(stderr, "lueur: resuming '%s' after %llu frames\n", options.resume_path.c_str(),
                 static_cast<unsigned long long>(film.frames));
  }
  print_render_header(options, job, std::to_string(pool.thread_count()) + " threads");

  const Clock::time_point start = Clock::now();
  Clock::time_point last_progress = start, last_checkpoint = start;
  RunFigures figures;
  const bool tty = ::isatty(STDERR_FILENO);
  const double time_limit = options.settings.time_limit;
  const double target_noise = options.settings.target_noise;
  bool stopped_by_noise = false, out_of_time = false;
  RunningNoiseEstimate running_noise;  // for the target, remade at powers of two of the frames
  const uint64_t first = film.frames;
  const InterruptCatcher interrupts;  // from here on, Ctrl-C stops after the frame in flight and keeps the frames
  int interrupted_by = 0;
  while (film.frames < static_cast<uint64_t>(frames)) {
    const FrameResult frame = render_frame_pair(traced, camera, settings, job.left, right ? &right->render : nullptr,
                                                right_side, pool, figures.tally);
    figures.cache = frame.cache;
    const double elapsed = seconds_since(start);
    const uint64_t done = film.frames;
    out_of_time = time_limit > 0.0 && elapsed >= time_limit;
    record_noise_history(options, film, elapsed, figures);
    bool quiet_enough = false;
    if (target_noise > 0.0) {
      const NoiseEstimate& noise =
          running_noise.update(film, settings.enabled, options.settings.weights, settings.sampler).image;
      // Confirmed by a full estimate, so that the summary's figure is below the target too.
      quiet_enough = noise.known && noise.rel_mse < target_noise &&
                     estimate_image_noise(film, settings.enabled, options.settings.weights, settings.sampler).rel_mse <
                         target_noise;
    }
    if (done == static_cast<uint64_t>(frames) || out_of_time || quiet_enough || seconds_since(last_progress) > 0.5) {
      last_progress = Clock::now();
      const double left = elapsed / static_cast<double>(done - first) * static_cast<double>(frames - done);
      std::fprintf(stderr, "%slueur: frame %llu/%d, %.1f s elapsed, about %.1f s left%s", tty ? "\r" : "",
                   static_cast<unsigned long long>(done), frames, elapsed, left, tty ? "   " : "\n");
    }
    if (quiet_enough) {
      std::fprintf(stderr, "%slueur: target noise %g reached after %llu frames, %.2f s\n", tty ? "\n" : "",
                   target_noise, static_cast<unsigned long long>(done), elapsed);
      stopped_by_noise = true;
      break;
    }
    if (out_of_time) break;
    if ((interrupted_by = interrupts.caught()) != 0) break;
    if (options.checkpoint_seconds > 0.0 && seconds_since(last_checkpoint) >= options.checkpoint_seconds &&
        done < static_cast<uint64_t>(frames)) {
      figures.seconds = elapsed;
      write_checkpoint(options, job.left, right_side, traced, figures);
      last_checkpoint = Clock::now();
    }
  }
  figures.seconds = seconds_since(start);
  if (tty) std::fprintf(stderr, "\n");
  finish_render(options, job.left, right_side, traced, figures, out_of_time, stopped_by_noise, interrupted_by);
  print_run_summary(options, film, job.right_film(), figures);
  std::printf("%s\n", options.out_path.c_str());
  // The shell's convention for a process ended by a signal, so that a script sees the render was cut short.
  return interrupted_by != 0 ? 128 + interrupted_by : 0;
}

}  // namespace lueur
