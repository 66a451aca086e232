// The headless loading progress line (see load_progress_line.h).
#include "app/load_progress_line.h"

#include <cstdio>

#include "core/memory_budget.h"

namespace lueur {

LoadProgressLine::LoadProgressLine(std::string label, bool on_terminal)
    : label_(std::move(label)), on_terminal_(on_terminal), start_(Clock::now()), last_(start_) {
  if (on_terminal_) ticker_ = std::thread([this] { tick(); });
}

LoadProgressLine::~LoadProgressLine() { finish(); }

LoadProgress LoadProgressLine::callback() {
  if (!on_terminal_) return {};
  return [this](LoadStage stage, double done) { show(stage, done); };
}

void LoadProgressLine::show(LoadStage stage, double done) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const bool new_stage = stage != stage_ || !shown_;
  stage_ = stage;
  done_ = done;
  if (stopping_ || (!new_stage && seconds_since(last_) < 0.1)) return;
  draw();
}

void LoadProgressLine::draw() {
  last_ = Clock::now();
  char share[16] = "";
  if (done_ >= 0.0) std::snprintf(share, sizeof share, " %3.0f%%", 100.0 * std::min(done_, 1.0));
  // "\033[K" clears what a longer line before left on the right.
  std::fprintf(stderr, "\rlueur: loading %s: %s%s (%.1f s)\033[K", label_.c_str(), load_stage_name(stage_), share,
               seconds_since(start_));
  std::fflush(stderr);
  shown_ = true;
}

void LoadProgressLine::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return stopping_; }))
    if (shown_ && seconds_since(last_) >= 0.25) draw();
}

void LoadProgressLine::finish() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  if (!shown_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  shown_ = false;
}

std::string load_summary(const std::string& stage_times, uint64_t triangles) {
  std::string line = "lueur: loading stages: " + stage_times;
  const uint64_t peak = peak_resident_bytes();
  if (peak > 0 && triangles > 0) {
    char memory[96];
    std::snprintf(memory, sizeof memory, "; peak memory %s, %.0f bytes per triangle", format_bytes(peak).c_str(),
                  static_cast<double>(peak) / static_cast<double>(triangles));
    line += memory;
  }
  return line;
}

}  // namespace lueur
