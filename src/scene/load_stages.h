// The stages of opening a scene file, for progress lines and the time each took. Depends on nothing.
#pragma once

#include <chrono>
#include <functional>
#include <vector>

namespace lueur {

enum class LoadStage { kRead, kParse, kConvert, kNormals, kTextures, kBvh };
inline constexpr int kLoadStageCount = 6;

/// "reading", "parsing", ...: what the stage does, as progress lines say it.
inline const char* load_stage_name(LoadStage stage) {
  static const char* const names[kLoadStageCount] = {"reading",           "parsing and checking", "converting",
                                                     "computing normals", "loading textures",     "building the BVH"};
  return names[static_cast<int>(stage)];
}

/// Told, from the loading thread, the stage at hand and its share done (0 to 1; negative where it cannot be told).
using LoadProgress = std::function<void(LoadStage stage, double done)>;

/// How long one stage took.
struct StageTime {
  LoadStage stage = LoadStage::kRead;
  double seconds = 0.0;
};

/// Times the stages of one load and reports them as they go.
class StageClock {
 public:
  explicit StageClock(LoadProgress progress = {}) : progress_(std::move(progress)) {}

  /// Ends the stage at hand (if any) and starts `stage`.
  void start(LoadStage stage) {
    stop();
    current_ = stage;
    started_ = std::chrono::steady_clock::now();
    running_ = true;
    report(0.0);
  }
  /// The stage at hand is `done` (0 to 1, negative: unknown) done.
  void report(double done) const {
    if (progress_ && running_) progress_(current_, done);
  }
  /// Ends the stage at hand.
  void stop() {
    if (!running_) return;
    times_.push_back({current_, std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count()});
    running_ = false;
  }
  /// report() as a function to hand to a step that tells its share done; empty when nobody listens.
  std::function<void(double done)> reporter() const {
    if (!progress_) return {};
    return [this](double done) { report(done); };
  }
  const std::vector<StageTime>& times() const { return times_; }
  const LoadProgress& progress() const { return progress_; }

 private:
  LoadProgress progress_;
  LoadStage current_ = LoadStage::kRead;
  std::chrono::steady_clock::time_point started_;
  bool running_ = false;
  std::vector<StageTime> times_;
};

}  // namespace lueur
