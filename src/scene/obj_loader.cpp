// The OBJ loader's entry points: read the OBJ file (and the MTL files its mtllib lines name) within the memory
// budget, then run the steps: parse_obj (obj_read, on every core), the MTL scan (mtl_scan) and build_scene
// (obj_convert), timing each stage. Depends on core, scene and those steps only; tinyobjloader stays inside
// obj_convert.cpp.
// Never depends on GL, the BVH or the render passes.
#include "scene/obj_loader.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string_view>
#include <unordered_set>

#include "core/regular_file.h"
#include "scene/mtl_scan.h"
#include "scene/obj_convert.h"
#include "scene/obj_read.h"
#include "scene/obj_text.h"
#include "scene/scene_textures.h"

namespace lueur {
namespace {

using obj::MtlLib;
using obj::MtlSource;
using obj::ParsedObj;
using obj::too_large;
using std::string_view;

/// Reads a whole regular file; throws SceneError "cannot open 'path': reason". FIFOs, devices and directories
/// are refused (a FIFO would block, /dev/zero never ends), and so is a file too large for the memory budget.
std::string read_text_file(const std::string& path, const MemoryBudget& budget, const FileReadProgress& progress = {}) {
  const auto check_size = [&](uint64_t bytes) {
    if (const uint64_t needed = scene_memory_bytes(bytes, 0, 0, 0, 0); needed > budget.bytes)
      throw SceneError(path + ": " + too_large("a " + format_bytes(bytes) + " file needs", needed, budget));
  };
  try {
    return read_regular_file(path, check_size, progress);
  } catch (const FileReadError& e) {
    throw SceneError(e.what());
  }
}

/// A UTF-8 byte-order mark would make tinyobjloader skip the first statement; it carries no meaning in OBJ.
void strip_bom(std::string& text) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
}

/// The file names of an mtllib line: blank-separated, with "\\ " keeping a blank inside a name (the same
/// escape tinyobjloader honours).
std::vector<std::string> split_mtllib(string_view s) {
  std::vector<std::string> names;
  std::string current;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '\\' && i + 1 < s.size()) {
      current += s[++i];
    } else if (obj::is_blank(s[i])) {
      if (!current.empty()) names.push_back(std::move(current));
      current.clear();
    } else {
      current += s[i];
    }
  }
  if (!current.empty()) names.push_back(std::move(current));
  return names;
}

/// Reads the MTL files named by the mtllib lines, beside the OBJ file. Unreadable ones become warnings.
/// Each MTL file named, read or not, goes into `files`, stamped before it is read.
std::vector<MtlSource> read_mtl_files(const std::string& obj_path, const std::string& label, const ParsedObj& s,
                                      const MemoryBudget& budget, std::vector<std::string>& warnings,
                                      std::vector<WatchedFile>& files) {
  namespace fs = std::filesystem;
  const fs::path directory = fs::path(obj_path).parent_path();
  std::vector<MtlSource> sources;
  std::unordered_set<std::string> seen;
  for (const MtlLib& lib : s.mtllibs) {
    // A single name with spaces is tried first; otherwise the line lists several names.
    std::vector<std::string> names{lib.names};
    std::error_code ec;
    if (!fs::exists(directory / lib.names, ec)) names = split_mtllib(lib.names);
    for (const std::string& name : names) {
      if (!seen.insert(name).second) continue;
      const std::string mtl_path = (directory / name).string();
      files.push_back({mtl_path, stamp_file(mtl_path)});
      try {
        MtlSource source{name, read_text_file(mtl_path, budget)};
        strip_bom(source.text);
        sources.push_back(std::move(source));
      } catch (const SceneError& e) {
        warnings.push_back(label + ":" + std::to_string(lib.line) + ": " + e.what() + ": using grey diffuse");
      }
    }
  }
  return sources;
}

/// How parse_obj runs for these options, reporting through `clock`.
obj::ReadSchedule schedule_of(const LoadOptions& options, const StageClock& clock) {
  obj::ReadSchedule schedule;
  schedule.threads = options.threads;
  schedule.chunk_bytes = options.chunk_bytes;
  schedule.progress = clock.reporter();
  return schedule;
}

std::string scene_name_of(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  return stem.empty() ? path : stem;
}

/// The scene's budget with its emitters counted (returned); refuses a scene whose emitters tip it over the budget.
uint64_t add_emitters_to_budget(const Scene& scene, const std::string& label, uint64_t scene_bytes,
                                const MemoryBudget& budget) {
  // The file's own emitters: the default light rig (a dozen triangles, added to a scene without any) costs nothing
  // worth counting.
  const auto own = static_cast<size_t>(std::count_if(scene.emitters.begin(), scene.emitters.end(),
                                                     [&](uint32_t t) { return t < scene.rig_begin; }));
  const uint64_t emitter_bytes = emitter_memory_bytes(own);
  uint64_t needed = 0;
  if (__builtin_add_overflow(scene_bytes, emitter_bytes, &needed)) needed = std::numeric_limits<uint64_t>::max();
  if (needed > budget.bytes)
    throw SceneError(label + ": " +
                     obj::too_large("its " + obj::counted(own, "emitting triangle") +
                                        " (light sampling's records and trees) and the rest of the scene need",
                                    needed, budget));
  return needed;
}

}  // namespace

uint64_t scene_memory_bytes(uint64_t text_bytes, uint64_t vertices, uint64_t normals, uint64_t texcoords,
                            uint64_t triangles) {
  // Fitted, with room to spare, to the peaks of the reader that came before Lueur's own (tinyobjloader, which held
  // the text twice and its own index arrays); the present reader and lean BVH need far less (BENCHMARKS.md,
  // "Loading big scenes"), so the budget errs on the safe side. A refit must keep --accel embree's own copy of the
  // triangles in mind and re-check which of the hostile corpus's budget cases are refused.
  constexpr uint64_t kPerTextByte = 3, kPerVertex = 48, kPerNormal = 32, kPerTexcoord = 24, kPerTriangle = 256;
  const uint64_t parts[][2] = {{text_bytes, kPerTextByte},
                               {vertices, kPerVertex},
                               {normals, kPerNormal},
                               {texcoords, kPerTexcoord},
                               {triangles, kPerTriangle}};
  uint64_t total = 0;
  for (const auto& [count, bytes] : parts) {
    uint64_t part = 0;
    if (__builtin_mul_overflow(count, bytes, &part) || __builtin_add_overflow(total, part, &total))
      return std::numeric_limits<uint64_t>::max();  // a sparse file of exabytes must not wrap around to a small figure
  }
  return total;
}

uint64_t emitter_memory_bytes(uint64_t emitters) {
  // Measured: 200000 scattered emitting triangles peaked 69 MB above the same file with Ke 0 (345 bytes each: the
  // emitter records, the light table, the clusters and the trees inside them); budgeted with 1.4x to spare.
  constexpr uint64_t kPerEmitter = 480;
  uint64_t bytes = 0;
  return __builtin_mul_overflow(emitters, kPerEmitter, &bytes) ? std::numeric_limits<uint64_t>::max() : bytes;
}

LoadedScene load_obj(const std::string& path, const LoadOptions& options) {
  const MemoryBudget budget = options.memory ? *options.memory : available_memory();
  StageClock clock(options.progress);
  clock.start(LoadStage::kRead);
  std::vector<WatchedFile> files{{path, stamp_file(path)}};
  std::string text = read_text_file(path, budget, [&](uint64_t read, uint64_t size) {
    clock.report(size > 0 ? static_cast<double>(read) / static_cast<double>(size) : 1.0);
  });
  strip_bom(text);
  clock.start(LoadStage::kParse);
  ParsedObj parsed = obj::parse_obj(text, path, budget, schedule_of(options, clock));
  const uint64_t text_bytes = text.size();
  std::string().swap(text);  // the chunks hold all the scene needs (assigning "" would keep the buffer)
  release_free_memory();
  clock.start(LoadStage::kConvert);
  std::vector<std::string> mtl_warnings;
  std::vector<MtlSource> sources = read_mtl_files(path, path, parsed, budget, mtl_warnings, files);
  parsed.warnings.insert(parsed.warnings.end(), mtl_warnings.begin(), mtl_warnings.end());
  const obj::ObjCounts& n = parsed.totals;
  uint64_t scene_bytes = scene_memory_bytes(text_bytes, n.vertices, n.normals, n.texcoords, n.triangles);
  LoadedScene loaded = obj::build_scene(parsed, path, scene_name_of(path), sources, options, clock);
  scene_bytes = add_emitters_to_budget(loaded.scene, path, scene_bytes, budget);
  clock.start(LoadStage::kTextures);
  // Texture names are relative to the MTL file that gives them; MTL files are named relative to the OBJ's folder.
  namespace fs = std::filesystem;
  const fs::path directory = fs::path(path).parent_path();
  std::vector<std::string> directories{directory.empty() ? std::string(".") : directory.string()};
  for (const MtlSource& source : sources) {
    const fs::path mtl_directory = (directory / source.label).parent_path();
    if (std::find(directories.begin(), directories.end(), mtl_directory.string()) == directories.end())
      directories.push_back(mtl_directory.string());
  }
  const uint64_t texture_budget = budget.bytes > scene_bytes ? budget.bytes - scene_bytes : 0;
  obj::load_scene_textures(loaded.scene, directories, texture_budget, path, loaded.warnings, files, options.threads,
                           clock.reporter());
  clock.stop();
  loaded.files = std::move(files);
  loaded.stage_times = clock.times();
  return loaded;
}

LoadedScene load_obj_from_text(const std::string& obj_text, const std::string& mtl_text, const std::string& name,
                               const LoadOptions& options) {
  const MemoryBudget budget = options.memory ? *options.memory : available_memory();
  StageClock clock(options.progress);
  std::string text = obj_text;
  strip_bom(text);
  clock.start(LoadStage::kParse);
  ParsedObj parsed = obj::parse_obj(text, name, budget, schedule_of(options, clock));
  clock.start(LoadStage::kConvert);
  std::vector<MtlSource> sources;
  if (!parsed.mtllibs.empty()) {
    const std::vector<std::string> names = split_mtllib(parsed.mtllibs.front().names);
    MtlSource source{names.empty() ? scene_name_of(name) + ".mtl" : names.front(), mtl_text};
    strip_bom(source.text);
    sources.push_back(std::move(source));
  }
  const obj::ObjCounts& n = parsed.totals;
  const uint64_t scene_bytes = scene_memory_bytes(text.size(), n.vertices, n.normals, n.texcoords, n.triangles);
  LoadedScene loaded = obj::build_scene(parsed, name, scene_name_of(name), sources, options, clock);
  add_emitters_to_budget(loaded.scene, name, scene_bytes, budget);
  clock.start(LoadStage::kTextures);
  std::vector<WatchedFile> no_files;
  obj::load_scene_textures(loaded.scene, {}, 0, name, loaded.warnings, no_files);
  clock.stop();
  loaded.stage_times = clock.times();
  return loaded;
}

}  // namespace lueur
