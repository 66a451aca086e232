// The conversion step of the OBJ loader (see obj_convert.h), one function per step: the MTL's materials, relabel
// their warnings, gather positions, normals and materials, emit the triangles (chunks in parallel), check and
// explain what came out, shading normals, emitters. Depends on core, scene, the loader's own pieces and
// tinyobjloader (for MTL files only); this is the only file that includes tiny_obj_loader.h. Never depends on GL,
// the BVH or the render passes.
#include "scene/obj_convert.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_set>

#include "core/thread_pool.h"
#include "scene/light_rig.h"
#include "scene/obj_text.h"
#include "scene/polygon.h"

namespace lueur::obj {
namespace {

using std::string_view;

/// NaN and negative values become 0, values above `maximum` become `maximum`.
float clamp_value(float v, float maximum) { return std::isfinite(v) && v > 0.0f ? std::min(v, maximum) : 0.0f; }

Vec3 clamp_value(const Vec3& v, float maximum) {
  return Vec3(clamp_value(v.x, maximum), clamp_value(v.y, maximum), clamp_value(v.z, maximum));
}

/// The MTL illumination models that ray-trace: 3 and 5 reflect (a mirror), 4, 6 and 7 also refract (glass). The rest
/// (0-2, 8-10: colour, ambient, highlight, and reflection without ray tracing) keep the BRDF.
SurfaceKind surface_of_illum(int illum) {
  if (illum == 3 || illum == 5) return SurfaceKind::kMirror;
  if (illum == 4 || illum == 6 || illum == 7) return SurfaceKind::kGlass;
  return SurfaceKind::kBrdf;
}

/// The MTL stream's materials as tinyobjloader reads them, with its name table; its warnings go to `warnings_text`.
/// An OBJ without a usable mtllib line has no materials, whatever MTL text there is.
struct FileMaterials {
  std::vector<tinyobj::material_t> materials;
  std::map<std::string, int> by_name;
};

FileMaterials load_materials(const ParsedObj& parsed, const std::string& mtl_text, std::string& warnings_text) {
  FileMaterials file;
  if (parsed.mtllibs.empty()) return file;
  std::istringstream stream(mtl_text);
  std::string errors;
  tinyobj::LoadMtl(&file.by_name, &file.materials, &stream, &warnings_text, &errors);
  return file;
}

/// Keeps tinyobjloader's MTL warnings, each once and labelled: those ending in "(line N in .mtl.)" with the MTL file
/// when there is only one, the rest with the OBJ.
void relabel_mtl_warnings(string_view text, const std::string& label, const std::vector<MtlSource>& mtl_sources,
                          std::vector<std::string>& warnings) {
  std::unordered_set<std::string> seen;
  for_each_line(text, [&](size_t, string_view line) {
    line = trim(line);
    if (line.empty() || line == ".") return;
    const bool about_mtl = line.find("in .mtl") != string_view::npos && mtl_sources.size() == 1;
    const std::string& where = about_mtl ? mtl_sources.front().label : label;
    if (seen.insert(std::string(line)).second) warnings.push_back(where + ": " + std::string(line));
  });
}

/// The chunks' positions and texture coordinates, in file order; each chunk's arrays are released once copied.
void gather_positions(ParsedObj& parsed, Scene& scene) {
  scene.positions.reserve(parsed.totals.vertices + 4);  // room for the default light
  scene.texcoords.reserve(parsed.totals.texcoords);
  for (ObjChunk& chunk : parsed.chunks) {
    scene.positions.insert(scene.positions.end(), chunk.positions.begin(), chunk.positions.end());
    scene.texcoords.insert(scene.texcoords.end(), chunk.texcoords.begin(), chunk.texcoords.end());
    free_array(chunk.positions);
    free_array(chunk.texcoords);
  }
}

/// File normals, normalised (those already of unit length kept bit for bit); unusable ones (zero, NaN, overflow)
/// leave their corners on the geometric normal. Returns, per file normal, its index in scene.normals or kNoNormal.
std::vector<uint32_t> gather_normals(ParsedObj& parsed, const std::string& label, Scene& scene,
                                     std::vector<std::string>& warnings) {
  std::vector<uint32_t> normal_remap;
  normal_remap.reserve(parsed.totals.normals);
  scene.normals.reserve(parsed.totals.normals);
  size_t unusable_normals = 0;
  for (ObjChunk& chunk : parsed.chunks) {
    for (const Vec3& n : chunk.normals) {
      const float length = glm::length(n);
      if (length > 0.0f && std::isfinite(length) && is_finite(n / length)) {
        normal_remap.push_back(static_cast<uint32_t>(scene.normals.size()));
        // A normal of unit length up to float rounding is kept as written: dividing by its length would move its
        // last bits, and a scene written out (--export-scene) would not read back as the same scene.
        const bool unit = std::abs(length - 1.0f) <= 4.0f * std::numeric_limits<float>::epsilon();
        scene.normals.push_back(unit ? n : n / length);
      } else {
        normal_remap.push_back(kNoNormal);
        ++unusable_normals;
      }
    }
    free_array(chunk.normals);
  }
  if (unusable_normals > 0)
    warnings.push_back(label + ": " + counted(unusable_normals, "unusable normal") +
                       " (zero or not finite): the geometric normal is used there");
  return normal_remap;
}

/// The file's materials as scene materials, and the grey default that faces without one share.
struct MaterialTable {
  std::vector<int64_t> remap;  ///< per tinyobjloader material: its scene material, or -1 (nameless)
  std::unordered_set<std::string> known_names;
  std::optional<uint32_t> default_material;  ///< appended on first use only
  size_t default_triangles = 0;
};

/// tinyobjloader also returns nameless materials (an empty MTL, a second mtllib); those are dropped and their faces,
/// like faces with material -1, get the grey default. The one-value forms ("Kd 0.25") are repaired from the scan.
MaterialTable gather_materials(const std::vector<tinyobj::material_t>& file_materials,
                               const std::vector<MtlEntry>& mtl_entries, Scene& scene) {
  const bool entries_match =
      mtl_entries.size() == static_cast<size_t>(std::count_if(file_materials.begin(), file_materials.end(),
                                                              [](const auto& m) { return !m.name.empty(); }));
  MaterialTable table;
  table.remap.assign(file_materials.size(), -1);
  size_t named = 0;
  for (size_t i = 0; i < file_materials.size(); ++i) {
    const tinyobj::material_t& m = file_materials[i];
    if (m.name.empty()) continue;
    Material material;
    material.name = m.name;
    material.kd = Vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    material.ks = Vec3(m.specular[0], m.specular[1], m.specular[2]);
    material.ke = Vec3(m.emission[0], m.emission[1], m.emission[2]);
    material.ns = m.shininess;
    material.tf = Vec3(m.transmittance[0], m.transmittance[1], m.transmittance[2]);
    material.diffuse_map = m.diffuse_texname;
    material.alpha_map = m.alpha_texname;
    int illum = known_illum(m.illum) ? m.illum : kDefaultIllum;
    bool has_ni = true, has_tf = true;
    if (entries_match) {
      const MtlEntry& entry = mtl_entries[named];
      if (entry.single_value[0]) material.kd = Vec3(material.kd.r);
      if (entry.single_value[1]) material.ks = Vec3(material.ks.r);
      if (entry.single_value[2]) material.ke = Vec3(material.ke.r);
      if (entry.single_value[3]) material.tf = Vec3(material.tf.r);
      illum = entry.illum;
      has_ni = entry.has_ni;
      has_tf = entry.has_tf;
      // No Ns: exponent 0, the lobe the report's mix turns into Lambert (so a closed box of albedo rho still
      // reflects rho of the light, whatever K), where tinyobjloader's default of 1 made a faint lobe that loses
      // energy (L1 1% and L2 3% low in a closed emitting box at K = 0.7).
      if (!entry.has_ns) material.ns = 0.0f;
    }
    ++named;
    // The MTL scan already warned, with file and line, about every value clamped here.
    material.kd = clamp_value(material.kd, mtl_maximum("Kd"));
    material.ks = clamp_value(material.ks, mtl_maximum("Ks"));
    material.ke = clamp_value(material.ke, mtl_maximum("Ke"));
    material.ns = clamp_value(material.ns, mtl_maximum("Ns"));
    material.surface = surface_of_illum(illum);
    if (material.surface == SurfaceKind::kGlass) {
      // Only glass reads Ni and Tf (most MTL files write them for every material, as exporters' defaults).
      const float ior = static_cast<float>(m.ior);
      material.ior = has_ni && std::isfinite(ior) && ior > 0.0f ? std::min(ior, mtl_maximum("Ni")) : kDefaultIor;
      material.tf = has_tf ? clamp_value(material.tf, mtl_maximum("Tf")) : Vec3(1.0f);  // no filter: clear
    } else {
      material.tf = Vec3(1.0f);
    }
    table.remap[i] = static_cast<int64_t>(scene.materials.size());
    table.known_names.insert(m.name);
    scene.materials.push_back(material);
  }
  return table;
}

/// The grey default material's index, appended to the scene the first time a face needs it.
uint32_t default_material_index(MaterialTable& table, Scene& scene) {
  if (!table.default_material) {
    Material grey;  // kd 0.5, nothing else
    if (table.known_names.count(grey.name)) grey.name = "lueur-default";
    table.default_material = static_cast<uint32_t>(scene.materials.size());
    scene.materials.push_back(grey);
  }
  ++table.default_triangles;
  return *table.default_material;
}

/// The scene material of each chunk's usemtl lines, and of the faces a chunk starts with (above its first usemtl:
/// the material in force at the end of the chunks before). Faces without a known material get the grey default.
struct FaceMaterials {
  std::vector<std::vector<uint32_t>> of_usemtl;  ///< per chunk, per usemtl line
  std::vector<uint32_t> incoming;                ///< per chunk
};

FaceMaterials resolve_face_materials(const ParsedObj& parsed, const FileMaterials& file, MaterialTable& table,
                                     Scene& scene) {
  const auto scene_material = [&](const UseMtl& use) -> int64_t {
    if (!use.after_mtllib) return -1;
    const auto it = file.by_name.find(use.name);
    if (it == file.by_name.end() || it->second < 0 || static_cast<size_t>(it->second) >= table.remap.size()) return -1;
    return table.remap[static_cast<size_t>(it->second)];
  };
  FaceMaterials faces;
  int64_t current = -1;
  const auto take = [&](int64_t material, bool used) -> uint32_t {
    if (material >= 0) return static_cast<uint32_t>(material);
    return used ? default_material_index(table, scene) : 0;  // a material no face takes is never looked at
  };
  for (const ObjChunk& chunk : parsed.chunks) {
    const uint64_t head = chunk.runs.empty() ? chunk.counts.faces : chunk.runs.front().first_face;
    faces.incoming.push_back(take(current, head > 0));
    std::vector<uint32_t>& of_usemtl = faces.of_usemtl.emplace_back(chunk.usemtls.size(), 0);
    for (size_t r = 0; r < chunk.runs.size(); ++r) {
      const MaterialRun& run = chunk.runs[r];
      const uint64_t end = r + 1 < chunk.runs.size() ? chunk.runs[r + 1].first_face : chunk.counts.faces;
      current = scene_material(chunk.usemtls[run.usemtl]);
      of_usemtl[run.usemtl] = take(current, end > run.first_face);
    }
  }
  return faces;
}

/// Writes one chunk's faces as triangles from `first` on, triangulating polygons (polygon.h); releases its corners.
/// Returns how many it wrote: fewer than its faces promised where a polygon had no ear left.
uint64_t convert_faces(ObjChunk& chunk, uint32_t incoming, const std::vector<uint32_t>& of_usemtl,
                       const std::vector<uint32_t>& normal_remap, Scene& scene, uint64_t first) {
  Triangle* out = scene.triangles.data() + first;
  const Corner* corner = chunk.corners.data();
  size_t large = 0, run = 0;
  uint32_t material = incoming;
  std::vector<Vec3> points;
  std::vector<std::array<uint32_t, 3>> split;
  const auto make = [&](const Corner& a, const Corner& b, const Corner& c) {
    Triangle tri;
    const Corner* abc[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      tri.v[k] = abc[k]->v;
      tri.t[k] = abc[k]->t;
      tri.n[k] = abc[k]->n == kNoIndex ? kNoNormal : normal_remap[abc[k]->n];
    }
    tri.material = material;
    *out++ = tri;
  };
  for (uint64_t f = 0; f < chunk.face_sizes.size(); ++f) {
    while (run < chunk.runs.size() && chunk.runs[run].first_face == f) material = of_usemtl[chunk.runs[run++].usemtl];
    const size_t k = chunk.face_sizes[f] == 255 ? chunk.large_face_sizes[large++] : chunk.face_sizes[f];
    if (k == 3) {
      make(corner[0], corner[1], corner[2]);
    } else {
      points.resize(k);
      for (size_t c = 0; c < k; ++c) points[c] = scene.positions[corner[c].v];
      split.clear();
      triangulate_face(points, split);
      for (const auto& [a, b, c] : split) make(corner[a], corner[b], corner[c]);
    }
    corner += k;
  }
  free_array(chunk.corners);
  free_array(chunk.face_sizes);
  free_array(chunk.large_face_sizes);
  return static_cast<uint64_t>(out - (scene.triangles.data() + first));
}

/// Every chunk's triangles in file order, with their normals and materials: chunks in parallel, each writing where
/// the faces before it end; then, where polygons lost triangles, the later chunks' triangles are moved up.
void gather_triangles(ParsedObj& parsed, const std::vector<uint32_t>& normal_remap, const FaceMaterials& materials,
                      unsigned threads, Scene& scene) {
  scene.triangles.resize(parsed.totals.triangles);
  std::vector<uint64_t> written(parsed.chunks.size(), 0);
  ThreadPool(static_cast<int>(threads)).parallel_for(static_cast<int>(parsed.chunks.size()), [&](int k, int) {
    written[k] = convert_faces(parsed.chunks[k], materials.incoming[k], materials.of_usemtl[k], normal_remap, scene,
                               parsed.before[k].triangles);
  });
  uint64_t end = 0;
  for (size_t k = 0; k < parsed.chunks.size(); ++k) {
    const auto from = scene.triangles.begin() + static_cast<ptrdiff_t>(parsed.before[k].triangles);
    if (end != parsed.before[k].triangles)
      std::copy(from, from + static_cast<ptrdiff_t>(written[k]), scene.triangles.begin() + static_cast<ptrdiff_t>(end));
    end += written[k];
  }
  scene.triangles.resize(end);
}

/// A scene needs a triangle; fewer triangles than the faces promised is worth a warning.
void check_triangle_count(const Scene& scene, const ParsedObj& parsed, const std::string& label,
                          std::vector<std::string>& warnings) {
  const uint64_t expected = parsed.totals.triangles;
  if (scene.triangles.empty()) {
    if (expected > 0)
      throw SceneError(label + ": no triangles: triangulating its faces gave none (degenerate polygons)");
    throw SceneError(label + ": no triangles");
  }
  if (scene.triangles.size() < expected)
    warnings.push_back(label + ": " + counted(expected - scene.triangles.size(), "triangle") +
                       " of polygons lost in triangulation");
}

/// Says why faces ended up grey: no materials at all, faces before the first usemtl, or unknown material names
/// (the first five by line, then a count).
void explain_default_material(const MaterialTable& materials, const ParsedObj& summary, const std::string& label,
                              std::vector<std::string>& warnings) {
  if (materials.default_triangles == 0) return;
  if (summary.mtllibs.empty()) {
    warnings.push_back(label + ": no materials: using grey diffuse");
    return;
  }
  if (summary.triangles_before_usemtl > 0)
    warnings.push_back(label + ": " + counted(summary.triangles_before_usemtl, "triangle") +
                       " before the first usemtl: using grey diffuse");
  std::unordered_set<std::string> reported;
  size_t unreported = 0;
  for (const UseMtl& use : summary.usemtls) {
    if (use.after_mtllib && materials.known_names.count(use.name)) continue;
    if (!reported.insert(use.name).second) continue;
    if (reported.size() > 5) {
      ++unreported;
      continue;
    }
    warnings.push_back(label + ":" + std::to_string(use.line) + ": unknown material '" + printable(use.name) +
                       "': using grey diffuse");
  }
  if (unreported > 0)
    warnings.push_back(label + ": " + counted(unreported, "more unknown material") + ": using grey diffuse");
}

/// Counts the triangles that can never light or be sampled: zero area, or area beyond float.
void report_degenerate_triangles(const Scene& scene, const std::string& label, std::vector<std::string>& warnings) {
  size_t zero_area = 0, zero_area_emitters = 0, overflowing = 0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const float area = scene.area(t);
    if (!(area > 0.0f)) {
      ++zero_area;
      if (scene.material_of(t).emissive()) ++zero_area_emitters;
    } else if (!std::isfinite(area)) {
      ++overflowing;  // edges beyond about 1e19: their cross product overflows float
    }
  }
  if (zero_area > 0) {
    std::string message = label + ": " + counted(zero_area, "zero-area triangle") + " (kept; never lights";
    if (zero_area_emitters > 0) {
      message += "; ";
      message += std::to_string(zero_area_emitters);
      message += " of them emissive";
    }
    message += ')';
    warnings.push_back(message);
  }
  if (overflowing > 0)
    warnings.push_back(label + ": " + counted(overflowing, "triangle") +
                       " too large for float arithmetic (area overflows; kept, never lights)");
}

/// File normals are the author's; computed ones only stand in when the file references none.
void assign_shading_normals(const ParsedObj& summary, const LoadOptions& options, Scene& scene,
                            const StageClock& clock) {
  if (summary.references_normals) return;
  if (options.smooth_normals) {
    compute_smooth_normals(scene, options.crease_degrees, options.threads, clock.reporter());
  } else {
    clear_normals(scene);
  }
}

/// Fills scene.emitters, adding the default light rig when the file has no emitter (and the rig is on).
void ensure_emitter(const std::string& label, const LoadOptions& options, Scene& scene,
                    std::vector<std::string>& warnings) {
  collect_emitters(scene);
  if (!scene.emitters.empty()) return;
  if (!options.light_rig || !(options.light_rig_scale > 0.0f)) {
    warnings.push_back(label + ": no emitter, and the default light rig is off: nothing lights the scene");
    return;
  }
  const std::optional<Enclosure> room = find_enclosure(scene.bounds(), model_ray_cast(scene));
  const std::string what = add_light_rig(scene, room, options.light_rig_scale);
  warnings.push_back(label + ": no emitter: added the default light rig, " + what);
  // Around 1e20 and beyond, float spacing swallows any light small enough for its area to stay finite.
  if (scene.emitters.empty()) {
    const Box3 box = scene.bounds();
    char extent[64];
    std::snprintf(extent, sizeof extent, "%g",
                  static_cast<double>(std::max(max_abs_component(box.lo), max_abs_component(box.hi))));
    throw SceneError(label + ": no emitter, and coordinates up to " + extent +
                     " are too large for float to hold a default light rig");
  }
}

}  // namespace

LoadedScene build_scene(ParsedObj& parsed, const std::string& label, const std::string& scene_name,
                        const std::vector<MtlSource>& mtl_sources, const LoadOptions& options, StageClock& clock) {
  LoadedScene result;
  std::vector<std::string>& warnings = result.warnings;
  warnings = std::move(parsed.warnings);

  const MtlStream mtl = merge_mtl_sources(mtl_sources, warnings);
  std::string mtl_warnings;
  const FileMaterials file = load_materials(parsed, mtl.text, mtl_warnings);
  relabel_mtl_warnings(mtl_warnings, label, mtl_sources, warnings);

  Scene& scene = result.scene;
  scene.name = scene_name;
  // The shares reported are rough: how long each step takes on a scene of millions of triangles.
  gather_positions(parsed, scene);
  clock.report(0.15);
  const std::vector<uint32_t> normal_remap = gather_normals(parsed, label, scene, warnings);
  MaterialTable materials = gather_materials(file.materials, mtl.entries, scene);
  const FaceMaterials face_materials = resolve_face_materials(parsed, file, materials, scene);
  clock.report(0.3);
  gather_triangles(parsed, normal_remap, face_materials, options.threads, scene);
  clock.report(0.85);
  free_array(parsed.chunks);
  release_free_memory();

  check_triangle_count(scene, parsed, label, warnings);
  explain_default_material(materials, parsed, label, warnings);
  report_degenerate_triangles(scene, label, warnings);
  clock.start(LoadStage::kNormals);
  assign_shading_normals(parsed, options, scene, clock);
  ensure_emitter(label, options, scene, warnings);
  return result;
}

}  // namespace lueur::obj
