// Reading the texture files a scene's materials name (map_Kd, map_d) into Scene::textures. Internal to src/scene;
// depends on core, scene and texture only.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/file_watch.h"
#include "scene/scene.h"

namespace lueur::obj {

/// Loads every texture the materials name, each file once, looking for it in `directories` in order (the OBJ's, then
/// each MTL file's). A texture that is missing, unreadable or too large for `byte_limit` (all textures together) is
/// one warning, labelled `label`; its material then falls back to grey (map_Kd) or to no cutout (map_d). With no
/// directories (a scene given as text) no file is read, and each named texture is such a warning. Each texture file
/// goes into `files`, stamped before it is read; a missing one as the first place it would be found. The files are
/// read and decoded on `threads` threads (0: every core), with the same result whatever their number; `progress`,
/// when given, is told the share of the files done.
void load_scene_textures(Scene& scene, const std::vector<std::string>& directories, uint64_t byte_limit,
                         const std::string& label, std::vector<std::string>& warnings, std::vector<WatchedFile>& files,
                         unsigned threads = 0, const std::function<void(double done)>& progress = {});

}  // namespace lueur::obj
