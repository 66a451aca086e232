// Opens a scene on a background thread, so that the window keeps drawing (and the old scene keeps rendering)
// while a large OBJ is parsed and its BVH built; the panel shows its stages as they go.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/scene_source.h"
#include "core/stopwatch.h"
#include "scene/load_stages.h"

namespace lueur {

class SceneLoading {
 public:
  SceneLoading(std::string path, const SceneOptions& options, float aspect);
  ~SceneLoading();
  SceneLoading(const SceneLoading&) = delete;
  SceneLoading& operator=(const SceneLoading&) = delete;

  /// "loading X: building the BVH (1.2 s)".
  std::string status() const;
  /// The stage at hand's share done (0 to 1), or negative where it cannot be told.
  double stage_done() const;
  /// The stages finished so far, with their times: "reading 0.05 s".
  std::vector<std::string> finished_stages() const;
  bool finished() const;
  /// After finished(): the scene, or nullopt with error() set.
  std::optional<OpenedScene> take_result();
  std::string error() const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  Clock::time_point start_;
  mutable std::mutex mutex_;
  std::optional<LoadStage> stage_;  ///< none until the first stage starts
  double stage_done_ = -1.0;
  Clock::time_point stage_start_;
  std::vector<StageTime> finished_stages_;
  bool finished_ = false;
  std::optional<OpenedScene> result_;
  std::string error_;
  std::thread thread_;
};

}  // namespace lueur
