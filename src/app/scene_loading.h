// Opens a scene on a background thread, so that the window keeps drawing (and the old scene keeps rendering)
// while a large OBJ is parsed and its BVH built.
#pragma once

#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "app/scene_source.h"
#include "core/stopwatch.h"

namespace lueur {

class SceneLoading {
 public:
  SceneLoading(std::string path, const SceneOptions& options, float aspect);
  ~SceneLoading();
  SceneLoading(const SceneLoading&) = delete;
  SceneLoading& operator=(const SceneLoading&) = delete;

  /// "loading X: building the BVH of N triangles (1.2 s)".
  std::string status() const;
  bool finished() const;
  /// After finished(): the scene, or nullopt with error() set.
  std::optional<OpenedScene> take_result();
  std::string error() const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  Clock::time_point start_;
  mutable std::mutex mutex_;
  std::string stage_ = "starting";
  bool finished_ = false;
  std::optional<OpenedScene> result_;
  std::string error_;
  std::thread thread_;
};

}  // namespace lueur
