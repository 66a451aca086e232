// Texture files of a scene's materials (see scene_textures.h).
#include "scene/scene_textures.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "scene/obj_text.h"

namespace lueur::obj {
namespace {

namespace fs = std::filesystem;

/// Exporters on Windows write backslashes.
std::string with_slashes(std::string name) {
  std::replace(name.begin(), name.end(), '\\', '/');
  return name;
}

/// The first of `directories` holding `name`, as written or with slashes for backslashes.
std::string find_texture(const std::string& name, const std::vector<std::string>& directories) {
  const std::string slashed = with_slashes(name);
  for (const std::string& directory : directories) {
    for (const std::string& candidate : {name, slashed}) {
      const fs::path path = fs::path(directory) / candidate;
      std::error_code ec;
      if (fs::is_regular_file(path, ec)) return path.string();
    }
  }
  return {};
}

}  // namespace

void load_scene_textures(Scene& scene, const std::vector<std::string>& directories, uint64_t byte_limit,
                         const std::string& label, std::vector<std::string>& warnings,
                         std::vector<WatchedFile>& files) {
  // The file found (or, when none is, the name as written) -> its texture index, or -1 after a failure: each file
  // is read once and each failure said once, however many statements name it and however they spell its path.
  std::map<std::string, int32_t> loaded;
  uint64_t left = byte_limit;
  auto texture_for = [&](const std::string& name, const char* statement) -> int32_t {
    const std::string path = directories.empty() ? std::string() : find_texture(name, directories);
    const std::string& key = path.empty() ? name : path;
    const auto known = loaded.find(key);
    if (known != loaded.end()) return known->second;
    if (!directories.empty()) {
      // A missing texture is watched where it would be found first: beside the OBJ, with slashes.
      const std::string watched =
          path.empty() ? (fs::path(directories.front()) / with_slashes(name)).string() : path;
      files.push_back({watched, stamp_file(watched)});
    }
    std::string error;
    Texture texture;
    if (directories.empty())
      error = "not read (the scene was given as text, with no directory to look in)";
    else
      error = path.empty() ? "not found beside the OBJ or its MTL files" : load_texture(path, left, texture);
    int32_t index = -1;
    if (error.empty()) {
      left -= std::min(left, texture.bytes());
      texture.name = name;
      index = static_cast<int32_t>(scene.textures.size());
      scene.textures.push_back(std::move(texture));
    } else {
      warnings.push_back(label + ": " + statement + " '" + printable(name) + "': " + error +
                         (std::string(statement) == "map_Kd" ? ": using grey" : ": no cutout"));
    }
    loaded.emplace(key, index);
    return index;
  };
  for (Material& m : scene.materials) {
    if (!m.diffuse_map.empty()) {
      m.diffuse_texture = texture_for(m.diffuse_map, "map_Kd");
      if (m.diffuse_texture < 0) m.kd = Vec3(0.5f);
    }
    if (!m.alpha_map.empty()) m.alpha_texture = texture_for(m.alpha_map, "map_d");
  }
}

}  // namespace lueur::obj
