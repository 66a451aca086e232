// The headless loading progress line (see load_progress_line.h).
#include "app/load_progress_line.h"

#include <cstdio>

#include "core/memory_budget.h"

namespace lueur {

LoadProgressLine::LoadProgressLine(std::string label, bool on_terminal)
    : label_(std::move(label)), on_terminal_(on_terminal), start_(Clock::now()), last_(start_) {}

LoadProgressLine::~LoadProgressLine() { finish(); }

LoadProgress LoadProgressLine::callback() {
  if (!on_terminal_) return {};
  return [this](LoadStage stage, double done) { show(stage, done); };
}

void LoadProgressLine::show(LoadStage stage, double done) {
  const Clock::time_point now = Clock::now();
  if (shown_ && stage == stage_ && std::chrono::duration<double>(now - last_).count() < 0.1) return;
  stage_ = stage;
  last_ = now;
  char share[16] = "";
  if (done >= 0.0) std::snprintf(share, sizeof share, " %3.0f%%", 100.0 * std::min(done, 1.0));
  // "\033[K" clears what a longer line before left on the right.
  std::fprintf(stderr, "\rlueur: loading %s: %s%s (%.1f s)\033[K", label_.c_str(), load_stage_name(stage), share,
               seconds_since(start_));
  std::fflush(stderr);
  shown_ = true;
}

void LoadProgressLine::finish() {
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
