// The headless progress line of a scene being opened: on a terminal, one line updated in place with the stage, its
// share done and the time, redrawn a few times a second even while a stage says nothing; elsewhere (a log, a pipe)
// nothing until the summary, which names each stage's time.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "core/stopwatch.h"
#include "scene/load_stages.h"

namespace lueur {

class LoadProgressLine {
 public:
  /// `label`: what is being opened, as the line names it. `on_terminal`: whether stderr is one.
  LoadProgressLine(std::string label, bool on_terminal);
  ~LoadProgressLine();
  LoadProgressLine(const LoadProgressLine&) = delete;
  LoadProgressLine& operator=(const LoadProgressLine&) = delete;

  /// What open_scene is told: redraws the line at most ten times a second, and at each new stage.
  LoadProgress callback();
  /// Stops the redrawing and clears the line, so that what is printed next starts on a clean one.
  void finish();

 private:
  void show(LoadStage stage, double done);
  /// Draws the line as things stand; the caller holds mutex_.
  void draw();
  /// The redrawing thread: the time goes on even when a stage reports nothing for a while.
  void tick();

  std::string label_;
  bool on_terminal_;
  Clock::time_point start_;
  std::mutex mutex_;  ///< guards what follows, and the terminal
  std::condition_variable wake_;
  bool shown_ = false;
  bool stopping_ = false;
  Clock::time_point last_;
  LoadStage stage_ = LoadStage::kRead;
  double done_ = -1.0;  ///< the stage's share done; negative: not known
  std::thread ticker_;
};

/// "lueur: loading stages: reading 0.05 s, ...; peak memory 620 MiB, 155 bytes per triangle".
std::string load_summary(const std::string& stage_times, uint64_t triangles);

}  // namespace lueur
