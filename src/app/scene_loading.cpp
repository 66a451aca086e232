// The loading thread: every failure becomes a message, never an exception escaping the thread.
#include "app/scene_loading.h"

#include <cstdio>
#include <exception>
#include <new>

namespace lueur {

SceneLoading::SceneLoading(std::string path, const SceneOptions& options, float aspect)
    : path_(std::move(path)), start_(Clock::now()), stage_start_(start_) {
  thread_ = std::thread([this, options, aspect] {
    std::optional<OpenedScene> result;
    std::string error;
    try {
      result = open_scene(path_, options, aspect, available_memory(), [this](LoadStage stage, double done) {
        std::lock_guard lock(mutex_);
        if (!stage_ || *stage_ != stage) {
          if (stage_) finished_stages_.push_back({*stage_, seconds_since(stage_start_)});
          stage_ = stage;
          stage_start_ = Clock::now();
        }
        stage_done_ = done;
      });
    } catch (const std::bad_alloc&) {
      error = "out of memory while loading '" + path_ + "'";
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard lock(mutex_);
    result_ = std::move(result);
    error_ = std::move(error);
    finished_ = true;
  });
}

SceneLoading::~SceneLoading() { thread_.join(); }

std::string SceneLoading::status() const {
  const double seconds = seconds_since(start_);
  char elapsed[32];
  std::snprintf(elapsed, sizeof elapsed, " (%.1f s)", seconds);
  std::lock_guard lock(mutex_);
  return "loading " + (path_.empty() ? std::string("the default scene") : path_) + ": " +
         (stage_ ? load_stage_name(*stage_) : "starting") + elapsed;
}

double SceneLoading::stage_done() const {
  std::lock_guard lock(mutex_);
  return stage_done_;
}

std::vector<std::string> SceneLoading::finished_stages() const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> lines;
  for (const StageTime& time : finished_stages_) lines.push_back(describe_stage_times({time}));
  return lines;
}

bool SceneLoading::finished() const {
  std::lock_guard lock(mutex_);
  return finished_;
}

std::optional<OpenedScene> SceneLoading::take_result() {
  std::lock_guard lock(mutex_);
  return std::move(result_);
}

std::string SceneLoading::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

}  // namespace lueur
