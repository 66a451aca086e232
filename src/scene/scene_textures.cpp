// Texture files of a scene's materials (see scene_textures.h).
//
// The files are read and decoded on every thread, a batch at a time, and then taken in the materials' order as if
// one thread had read them one after the other: what fits the budget, the messages and the texture indices are the
// same whatever the thread count. Within a batch, the budget is first shared out assuming that every image whose
// header reads also decodes; the batch is then walked again in order with the real outcomes, and an image that
// fits only because one before it failed to decode is decoded there.
#include "scene/scene_textures.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "core/thread_pool.h"
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

/// One texture file the materials name, as first named, and what reading it gave.
struct Wanted {
  std::string name;       ///< as the first statement naming it wrote it
  const char* statement;  ///< that statement: "map_Kd" or "map_d"
  std::string path;       ///< where it was found; empty: nowhere
  std::string error;      ///< why it cannot be read at all, before any budget
  TextureFile file;
  std::string probe_error;
  int width = 0, height = 0;
  std::optional<std::string> decode_error;  ///< set once decoded (empty: success)
  Texture texture;
};

/// Reads the file and its header (no budget yet: the file is read when it is no larger than `byte_limit`, the most
/// any texture of the batch can be given).
void read_and_probe(Wanted& wanted, uint64_t byte_limit) {
  wanted.file = read_texture_file(wanted.path, byte_limit);
  if (wanted.file.read) wanted.probe_error = probe_texture(wanted.file.bytes, wanted.width, wanted.height);
}

/// Why `wanted` cannot be given `left` bytes of texels, or "" (the file's, then decode_texture's checks, in their
/// order, from what read_and_probe found).
std::string refusal(const Wanted& wanted, uint64_t left) {
  if (!wanted.error.empty()) return wanted.error;
  if (std::string error = texture_file_refusal(wanted.file, left); !error.empty()) return error;
  if (!wanted.probe_error.empty()) return wanted.probe_error;
  return check_texture_size(wanted.width, wanted.height, left);
}

}  // namespace

void load_scene_textures(Scene& scene, const std::vector<std::string>& directories, uint64_t byte_limit,
                         const std::string& label, std::vector<std::string>& warnings, std::vector<WatchedFile>& files,
                         unsigned threads, const std::function<void(double done)>& progress) {
  // The file found (or, when none is, the name as written) -> its place in `wanted`: each file is read once and
  // each failure said once, however many statements name it and however they spell its path.
  std::map<std::string, size_t> known;
  std::vector<Wanted> wanted;
  const auto wanted_for = [&](const std::string& name, const char* statement) {
    const std::string path = directories.empty() ? std::string() : find_texture(name, directories);
    const std::string& key = path.empty() ? name : path;
    if (const auto found = known.find(key); found != known.end()) return found->second;
    Wanted w;
    w.name = name;
    w.statement = statement;
    w.path = path;
    if (directories.empty()) {
      w.error = "not read (the scene was given as text, with no directory to look in)";
    } else {
      // A missing texture is watched where it would be found first: beside the OBJ, with slashes. Stamped now,
      // before it is read.
      const std::string watched =
          path.empty() ? (fs::path(directories.front()) / with_slashes(name)).string() : path;
      files.push_back({watched, stamp_file(watched)});
      if (path.empty()) w.error = "not found beside the OBJ or its MTL files";
    }
    known.emplace(key, wanted.size());
    wanted.push_back(std::move(w));
    return wanted.size() - 1;
  };
  std::vector<std::pair<size_t, size_t>> material_maps(scene.materials.size(), {~size_t{0}, ~size_t{0}});
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& material = scene.materials[m];
    if (!material.diffuse_map.empty()) material_maps[m].first = wanted_for(material.diffuse_map, "map_Kd");
    if (!material.alpha_map.empty()) material_maps[m].second = wanted_for(material.alpha_map, "map_d");
  }

  ThreadPool pool(static_cast<int>(threads));
  // A batch of a few files a thread: enough to keep every thread busy, few enough files held at once.
  const size_t batch = 4 * static_cast<size_t>(pool.thread_count());
  std::vector<int32_t> index(wanted.size(), -1);
  uint64_t left = byte_limit;
  for (size_t first = 0; first < wanted.size(); first += batch) {
    const size_t last = std::min(first + batch, wanted.size());
    const auto for_each_in_batch = [&](const std::function<void(Wanted&)>& work) {
      pool.parallel_for(static_cast<int>(last - first),
                        [&](int i, int) { work(wanted[first + static_cast<size_t>(i)]); });
    };
    for_each_in_batch([&](Wanted& w) {
      if (w.error.empty()) read_and_probe(w, left);
    });
    // The budget shared out as if every image that fits decodes; those decode on every thread.
    std::vector<bool> planned(last - first, false);
    uint64_t planned_left = left;
    for (size_t i = first; i < last; ++i) {
      if (!refusal(wanted[i], planned_left).empty()) continue;
      planned[i - first] = true;
      planned_left -= std::min(planned_left, texel_bytes(wanted[i].width, wanted[i].height));
    }
    pool.parallel_for(static_cast<int>(last - first), [&](int i, int) {
      if (!planned[static_cast<size_t>(i)]) return;
      Wanted& w = wanted[first + static_cast<size_t>(i)];
      w.decode_error = decode_probed_texture(w.file.bytes, w.width, w.height, w.texture);
    });
    // In order, with the real outcomes: the one-thread result.
    for (size_t i = first; i < last; ++i) {
      Wanted& w = wanted[i];
      std::string error = refusal(w, left);
      if (error.empty()) {
        if (!w.decode_error) w.decode_error = decode_probed_texture(w.file.bytes, w.width, w.height, w.texture);
        error = *w.decode_error;
      }
      if (error.empty()) {
        left -= std::min(left, w.texture.bytes());
        w.texture.name = w.name;
        index[i] = static_cast<int32_t>(scene.textures.size());
        scene.textures.push_back(std::move(w.texture));
      } else {
        warnings.push_back(label + ": " + w.statement + " '" + printable(w.name) + "': " + error +
                           (std::string(w.statement) == "map_Kd" ? ": using grey" : ": no cutout"));
      }
      std::string().swap(w.file.bytes);
      w.texture = Texture{};
    }
    if (progress) progress(static_cast<double>(last) / static_cast<double>(wanted.size()));
  }

  for (size_t m = 0; m < scene.materials.size(); ++m) {
    Material& material = scene.materials[m];
    if (material_maps[m].first != ~size_t{0}) {
      material.diffuse_texture = index[material_maps[m].first];
      if (material.diffuse_texture < 0) material.kd = Vec3(0.5f);
    }
    if (material_maps[m].second != ~size_t{0}) material.alpha_texture = index[material_maps[m].second];
  }
}

}  // namespace lueur::obj
