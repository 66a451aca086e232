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
        const std::string name = load_stage_name(stage);
        if (name != stage_) {
          if (stage_ != "starting") {
            char line[96];
            std::snprintf(line, sizeof line, "%s %.2f s", stage_.c_str(), seconds_since(stage_start_));
            finished_stages_.push_back(line);
          }
          stage_ = name;
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
  return "loading " + (path_.empty() ? std::string("the default scene") : path_) + ": " + stage_ + elapsed;
}

double SceneLoading::stage_done() const {
  std::lock_guard lock(mutex_);
  return stage_done_;
}

std::vector<std::string> SceneLoading::finished_stages() const {
  std::lock_guard lock(mutex_);
  return finished_stages_;
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
