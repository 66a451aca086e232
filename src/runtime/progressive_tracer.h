// The tracer thread of the viewer: accumulates frames of the current scene, camera and settings in the background,
// restarts at once when any of them changes, and publishes each finished frame as a snapshot that the display can
// take without ever waiting for a frame. Knows nothing of GL or the UI.
// This folder, runtime/, runs frames: the tracer thread of the window, the frames an MPI job deals out, the resume
// state of a render and the memory it will need. It sits on the integrator.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "core/camera.h"
#include "film/film.h"
#include "runtime/frame_turns.h"
#include "passes/render_settings.h"
#include "core/thread_pool.h"
#include "integrator/traced_scene.h"
#include "store/l1_cache.h"

namespace lueur {

/// Figures about the current accumulation, shown by the panel.
struct TracerStats {
  uint64_t frames = 0;    ///< full-resolution frames accumulated since the last restart
  uint64_t previews = 0;  ///< reduced-resolution preview frames rendered since the last restart
  double seconds = 0.0;   ///< time spent tracing them, previews included
  uint64_t rays = 0;      ///< rays traced since the last restart
  double last_frame_seconds = 0.0;
  double l2_seconds = 0.0;
  uint64_t l2_bounce_hits = 0, l2_reused = 0, l2_cached = 0;
  uint64_t ln_lookups = 0, ln_reused = 0, ln_cached = 0;  ///< ln's vertices past q that needed L1, and their sources
  uint64_t ln_paths = 0, ln_ended = 0;  ///< ln's paths, and those that ended at a cell's further light
  ServedSamples served;  ///< the samples of the store's cells that served L2's and ln's look-ups
  L1CacheStats cache;  ///< the L1 store after the last frame
  /// Where the accumulation stops whatever the frame limit: further frames would repeat earlier ones
  /// (frames_before_samples_repeat).
  uint64_t frames_before_repeat = 0;
  double mrays_per_second() const { return seconds > 0.0 ? static_cast<double>(rays) * 1e-6 / seconds : 0.0; }
};

/// One published frame: the sums and frame count of a film, always consistent with each other.
struct TracerSnapshot {
  Film film{FilmMode::kShownCopy};
  uint64_t generation = 0;  ///< which accumulation it belongs to; bumps at every restart
  int preview_divisor = 1;  ///< 1: full resolution; 8, 4, 2: a reduced-resolution preview right after a restart
  TracerStats stats;
  uint64_t version = 0;  ///< increases with every published snapshot
};

class ProgressiveTracer {
 public:
  /// `threads` <= 0: one per hardware thread. The tracer starts idle until it has a scene and a non-empty size.
  /// Its threads run at background priority, so that the display's thread always gets a core when it needs one.
  /// Tracers given the same `turns` render their frames one at a time, taking turns (an A/B split's two sides).
  explicit ProgressiveTracer(int threads = 0, std::shared_ptr<FrameTurns> turns = nullptr);
  ~ProgressiveTracer();
  ProgressiveTracer(const ProgressiveTracer&) = delete;
  ProgressiveTracer& operator=(const ProgressiveTracer&) = delete;

  // Each of these restarts the accumulation when the value differs from the current one.
  void set_scene(std::shared_ptr<const TracedScene> scene);
  void set_camera(const CameraSpec& camera);
  void set_settings(const RenderSettings& settings);  ///< a size of 0 in either direction idles the tracer
  void reset();

  // These do not restart.
  void set_paused(bool paused);
  void set_frame_limit(uint64_t frames);  ///< 0: no limit
  /// Stops accumulating once this many seconds were spent tracing since the last restart (the frame in flight
  /// finishes); 0: no limit.
  void set_time_limit(double seconds);
  /// Reduced-resolution previews after a restart (on by default); off makes every published frame full size.
  void set_previews(bool enabled);

  /// Moves the newest snapshot into `out` when it is newer than `out.version` and belongs to the current
  /// accumulation; returns whether it did. Never waits for a frame to finish.
  bool take_snapshot(TracerSnapshot& out);

  /// Blocks until the current accumulation has `frames` full-resolution frames, or `timeout_seconds` pass.
  bool wait_for_frames(uint64_t frames, double timeout_seconds);

  uint64_t generation() const;
  RenderSettings settings() const;
  TracerStats stats() const;
  bool idle() const;  ///< paused, a limit reached (frames, time, the sample sequences), no scene or empty size
  int thread_count() const { return pool_.thread_count(); }

 private:
  struct Job;
  void run();
  void restart_locked();
  bool can_work_locked() const;
  void publish(const Film& film, uint64_t generation, int divisor, const TracerStats& stats);

  ThreadPool pool_;
  std::shared_ptr<FrameTurns> turns_;  ///< null: the cores are this tracer's alone
  mutable std::mutex mutex_;
  std::condition_variable wake_, frame_done_;
  std::atomic<bool> cancel_{false};

  // Guarded by mutex_.
  std::shared_ptr<const TracedScene> scene_;
  CameraSpec camera_;
  RenderSettings settings_;
  bool paused_ = false, previews_ = true, stopping_ = false, dirty_ = true;
  uint64_t frame_limit_ = 0;
  double time_limit_ = 0.0;
  uint64_t generation_ = 0;
  TracerStats stats_;
  TracerSnapshot ready_;  ///< the newest published snapshot, swapped out by take_snapshot
  bool ready_valid_ = false;
  uint64_t next_version_ = 1;

  TracerSnapshot back_;  ///< the tracer thread's own buffer, filled outside the lock
  std::thread thread_;
};

}  // namespace lueur
