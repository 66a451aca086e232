// The tracer thread's loop: wait for work, render previews then full frames, publish each one.
#include "runtime/progressive_tracer.h"

#include <chrono>
#include <utility>

#include "core/stopwatch.h"
#include "integrator/renderer.h"

namespace lueur {
namespace {

/// Reduced-resolution steps after a restart, coarsest first; a step is skipped when the image would be tiny.
constexpr int kPreviewDivisors[] = {8, 4, 2};
constexpr int kMinPreviewPixels = 8;

}  // namespace

ProgressiveTracer::ProgressiveTracer(int threads, std::shared_ptr<FrameTurns> turns)
    : pool_(threads, ThreadPriority::kBackground), turns_(std::move(turns)) {
  stats_.frames_before_repeat = frames_before_samples_repeat(settings_);
  thread_ = std::thread([this] {
    set_current_thread_priority(ThreadPriority::kBackground);  // it works in the pool's loops too
    run();
  });
}

ProgressiveTracer::~ProgressiveTracer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    cancel_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void ProgressiveTracer::restart_locked() {
  ++generation_;
  dirty_ = true;
  cancel_ = true;
  ready_valid_ = false;  // a snapshot of the old accumulation must never be shown after the restart
  stats_ = TracerStats{};
  stats_.frames_before_repeat = frames_before_samples_repeat(settings_);
  wake_.notify_all();
  frame_done_.notify_all();
}

void ProgressiveTracer::set_scene(std::shared_ptr<const TracedScene> scene) {
  std::lock_guard lock(mutex_);
  if (scene == scene_) return;
  scene_ = std::move(scene);
  restart_locked();
}

void ProgressiveTracer::set_camera(const CameraSpec& camera) {
  std::lock_guard lock(mutex_);
  if (camera == camera_) return;
  camera_ = camera;
  restart_locked();
}

void ProgressiveTracer::set_settings(const RenderSettings& settings) {
  std::lock_guard lock(mutex_);
  if (settings == settings_) return;
  settings_ = settings;
  restart_locked();
}

void ProgressiveTracer::reset() {
  std::lock_guard lock(mutex_);
  restart_locked();
}

void ProgressiveTracer::set_paused(bool paused) {
  std::lock_guard lock(mutex_);
  paused_ = paused;
  wake_.notify_all();
}

void ProgressiveTracer::set_frame_limit(uint64_t frames) {
  std::lock_guard lock(mutex_);
  frame_limit_ = frames;
  wake_.notify_all();
}

void ProgressiveTracer::set_time_limit(double seconds) {
  std::lock_guard lock(mutex_);
  time_limit_ = seconds;
  wake_.notify_all();
}

void ProgressiveTracer::set_previews(bool enabled) {
  std::lock_guard lock(mutex_);
  previews_ = enabled;
}

bool ProgressiveTracer::take_snapshot(TracerSnapshot& out) {
  std::lock_guard lock(mutex_);
  if (!ready_valid_ || ready_.version <= out.version) return false;
  std::swap(out, ready_);
  ready_valid_ = false;
  return true;
}

bool ProgressiveTracer::wait_for_frames(uint64_t frames, double timeout_seconds) {
  std::unique_lock lock(mutex_);
  return frame_done_.wait_for(lock, std::chrono::duration<double>(timeout_seconds),
                              [&] { return stats_.frames >= frames; });
}

uint64_t ProgressiveTracer::generation() const {
  std::lock_guard lock(mutex_);
  return generation_;
}
RenderSettings ProgressiveTracer::settings() const {
  std::lock_guard lock(mutex_);
  return settings_;
}
TracerStats ProgressiveTracer::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}
bool ProgressiveTracer::idle() const {
  std::lock_guard lock(mutex_);
  return !can_work_locked();
}

bool ProgressiveTracer::can_work_locked() const {
  return !paused_ && scene_ && settings_.width > 0 && settings_.height > 0 &&
         (frame_limit_ == 0 || stats_.frames < frame_limit_) && (time_limit_ <= 0.0 || stats_.seconds < time_limit_) &&
         stats_.frames < stats_.frames_before_repeat;
}

void ProgressiveTracer::publish(const Film& film, uint64_t generation, int divisor, const TracerStats& stats) {
  // The copy happens on the tracer thread, outside the lock; the display only ever swaps buffers.
  back_.film.width = film.width;
  back_.film.height = film.height;
  back_.film.frames = film.frames;
  for (size_t l = 0; l < film.sums.size(); ++l) back_.film.sums[l].assign(film.sums[l].begin(), film.sums[l].end());
  // The noise estimate's snapshots change only at powers of two of the frame count: copied only when they differ.
  for (size_t c = 0; c < film.checkpoints.size(); ++c) {
    PassSnapshot& copy = back_.film.checkpoints[c];
    const PassSnapshot& checkpoint = film.checkpoints[c];
    bool same = copy.frames == checkpoint.frames && back_.generation == generation;
    for (size_t p = 0; p < checkpoint.sums.size(); ++p) same = same && copy.sums[p].size() == checkpoint.sums[p].size();
    if (same) continue;
    copy.frames = checkpoint.frames;
    for (size_t p = 0; p < checkpoint.sums.size(); ++p)
      copy.sums[p].assign(checkpoint.sums[p].begin(), checkpoint.sums[p].end());
  }
  back_.generation = generation;
  back_.preview_divisor = divisor;
  back_.stats = stats;
  std::lock_guard lock(mutex_);
  if (generation != generation_) return;  // restarted meanwhile: this frame is stale
  back_.version = next_version_++;
  std::swap(back_, ready_);
  ready_valid_ = true;
}

void ProgressiveTracer::run() {
  // The accumulation and, right after a restart, the reduced-resolution previews' own (their store learns apart).
  Accumulation accumulation, preview;
  std::shared_ptr<const TracedScene> scene;
  CameraSpec camera_spec;
  RenderSettings settings;
  uint64_t generation = 0;
  size_t preview_step = 0;
  bool previews = true;

  while (true) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || (can_work_locked() && (dirty_ || generation == generation_)); });
      if (stopping_) return;
      if (dirty_) {
        dirty_ = false;
        cancel_ = false;
        scene = scene_;
        camera_spec = camera_;
        settings = settings_;
        generation = generation_;
        previews = previews_;
        preview_step = 0;
        accumulation.reset(settings);
      }
    }

    // Previews right after a restart, then full frames.
    int divisor = 1;
    while (previews && preview_step < std::size(kPreviewDivisors)) {
      const int d = kPreviewDivisors[preview_step];
      if (settings.width / d >= kMinPreviewPixels && settings.height / d >= kMinPreviewPixels) {
        divisor = d;
        break;
      }
      ++preview_step;
    }
    RenderSettings frame_settings = settings;
    Accumulation* target = &accumulation;
    if (divisor > 1) {
      frame_settings.width = settings.width / divisor;
      frame_settings.height = settings.height / divisor;
      preview.reset(frame_settings);
      target = &preview;
    }
    const Camera camera = make_camera(camera_spec, frame_settings.width, frame_settings.height);

    FrameResult result;
    double seconds = 0.0;
    {
      const FrameTurn turn(turns_.get());
      const Clock::time_point start = Clock::now();
      result = render_frame(*scene, camera, frame_settings, *target, pool_, &cancel_);
      seconds = seconds_since(start);
    }
    if (!result.completed) continue;  // cancelled by a restart: the loop picks up the new job

    TracerStats stats;
    {
      std::lock_guard lock(mutex_);
      if (generation != generation_) continue;
      stats_.seconds += seconds;
      stats_.rays += result.rays;
      stats_.last_frame_seconds = seconds;
      stats_.l2_seconds += result.l2_seconds;
      stats_.l2_bounce_hits += result.l2_bounce_hits;
      stats_.l2_reused += result.l2_reused;
      stats_.l2_cached += result.l2_cached;
      stats_.ln_lookups += result.ln_lookups;
      stats_.ln_reused += result.ln_reused;
      stats_.ln_cached += result.ln_cached;
      stats_.ln_paths += result.ln_paths;
      stats_.ln_ended += result.ln_ended;
      stats_.served.add(result.served_samples);
      stats_.cache = result.cache;
      if (divisor == 1)
        stats_.frames = accumulation.film.frames;
      else
        ++stats_.previews;
      stats = stats_;
    }
    if (divisor > 1) ++preview_step;
    publish(target->film, generation, divisor, stats);
    frame_done_.notify_all();
  }
}

}  // namespace lueur
