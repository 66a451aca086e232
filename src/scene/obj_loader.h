// Loads a Wavefront OBJ (+ MTL) file into a Scene, rejecting malformed input with a file:line message.
// Depends on core and scene only; tinyobjloader stays inside obj_convert.cpp and never leaks into this header.
// The steps behind it: obj_read (with obj_parse), mtl_scan and obj_convert (with obj_text for the text they share).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/file_watch.h"
#include "core/memory_budget.h"
#include "scene/load_stages.h"
#include "scene/scene.h"

namespace lueur {

/// A scene that cannot be loaded. The message is one line and names the file, and the line where there is one:
/// "scene.obj:12: face index 40 out of range (file has 8 vertices so far)".
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// How the loader fills in what the file leaves out.
struct LoadOptions {
  /// Computes smooth shading normals (compute_smooth_normals) when the file has none. Normals written in the
  /// file are always used, whatever this says: they are the author's intent. With false and no file normals,
  /// every triangle is shaded flat with its geometric normal.
  bool smooth_normals = true;
  /// Faces meeting at a larger angle keep a sharp edge when normals are computed.
  float crease_degrees = 60.0f;
  /// Memory the loaded scene may take; unset: available_memory(). A file whose size or running vertex and
  /// triangle counts would need more is refused with "scene too large" while it is read.
  std::optional<MemoryBudget> memory;
  /// A scene without emitters gets the default light rig (add_light_rig), its radiance times `light_rig_scale`.
  /// Off, such a scene stays unlit (and says so).
  bool light_rig = true;
  float light_rig_scale = 1.0f;
  /// Threads that parse and convert the OBJ; 0: every core. The scene is the same whatever the count.
  unsigned threads = 0;
  /// The size of the pieces the OBJ text is parsed in (cut at line ends); 0: several per thread. The scene is the
  /// same whatever the size.
  size_t chunk_bytes = 0;
  /// Told each stage and its share done as the file is read and converted. May be empty.
  LoadProgress progress;
};

/// Bytes loading and preparing (BVH, light table) a scene of this size takes at its peak: a conservative
/// figure, measured on large scenes. `text_bytes` is the size of the OBJ text.
uint64_t scene_memory_bytes(uint64_t text_bytes, uint64_t vertices, uint64_t normals, uint64_t texcoords,
                            uint64_t triangles);

/// Bytes that light sampling adds for a scene's emitting triangles (their records, clusters and trees), on top of
/// scene_memory_bytes: known only once the materials say which triangles emit.
uint64_t emitter_memory_bytes(uint64_t emitters);

/// A loaded scene and what the loader repaired or guessed on the way (each a one-line message).
struct LoadedScene {
  Scene scene;
  std::vector<std::string> warnings;
  /// Every file the scene was read from or looked for, each stamped just before it was read: the OBJ, each MTL its
  /// mtllib lines name (found or not), each texture (where it was found; a missing one where it would be looked for
  /// first). The window reloads the scene when one of them changes. Empty for a scene given as text.
  std::vector<WatchedFile> files;
  /// How long each stage took (reading, parsing, converting, normals, textures).
  std::vector<StageTime> stage_times;
};

/// Loads `path` and the MTL files its `mtllib` lines name (looked up beside the OBJ file).
/// The result always has at least one triangle and one emitter (a default light is added when the file has
/// none) and `scene.emitters` is filled. Throws SceneError for missing, unreadable or malformed files, and
/// for a scene without emitters so far from the origin (about 1e20) that no default light fits in float.
/// Missing MTL files, unknown materials and bad material values are warnings: the faces get a grey diffuse
/// default material (kd 0.5). Zero-area triangles are kept (they are never emitters).
LoadedScene load_obj(const std::string& path, const LoadOptions& options = {});

/// The same loader on in-memory text (fuzzing and tests). `mtl_text` stands for the file(s) named by the
/// OBJ's `mtllib` lines, so an OBJ without `mtllib` gets no materials. `name` is used in messages as the
/// file name; `scene.name` is its stem.
LoadedScene load_obj_from_text(const std::string& obj_text, const std::string& mtl_text, const std::string& name,
                               const LoadOptions& options = {});

}  // namespace lueur
