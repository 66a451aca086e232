// The conversion step of the OBJ loader (see obj_convert.h), one function per step: parse, relabel the parser's
// warnings, gather positions, normals and materials, emit the triangles, check and explain what came out, shading
// normals, emitters. Depends on core, scene, the loader's own pieces and tinyobjloader; this is the only file that
// includes tiny_obj_loader.h. Never depends on GL, the BVH or the render passes.
#include "scene/obj_convert.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string_view>
#include <unordered_set>

#include "scene/light_rig.h"
#include "scene/obj_text.h"

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

/// Runs tinyobjloader on the validated text (triangulating); its first error line becomes a SceneError.
tinyobj::ObjReader parse_obj(const std::string& obj_text, const std::string& mtl_text, const std::string& label) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  const bool parsed = reader.ParseFromString(obj_text, mtl_text, config);
  if (!parsed || !reader.Error().empty()) {
    std::string error = reader.Error();
    error = error.substr(0, error.find('\n'));
    throw SceneError(label + ": " + (error.empty() ? std::string("tinyobjloader could not parse the file") : error));
  }
  return reader;
}

/// Keeps tinyobjloader's warnings, each once and labelled. Its "material not found" lines are dropped: ours name
/// the line (explain_default_material). Its MTL warnings end in "(line N in .mtl.)" and are labelled with the MTL
/// file when there is only one.
void relabel_parser_warnings(string_view text, const std::string& label, const std::vector<MtlSource>& mtl_sources,
                             std::vector<std::string>& warnings) {
  std::unordered_set<std::string> seen;
  for_each_line(text, [&](size_t, string_view line) {
    line = trim(line);
    if (line.empty() || line == "." || line.substr(0, 12) == "material [ '") return;
    const bool about_mtl = line.find("in .mtl") != string_view::npos && mtl_sources.size() == 1;
    const std::string& where = about_mtl ? mtl_sources.front().label : label;
    if (seen.insert(std::string(line)).second) warnings.push_back(where + ": " + std::string(line));
  });
}

void gather_positions(const tinyobj::attrib_t& attrib, Scene& scene) {
  const size_t vertex_count = attrib.vertices.size() / 3;
  scene.positions.reserve(vertex_count + 4);  // room for the default light
  for (size_t i = 0; i < vertex_count; ++i)
    scene.positions.emplace_back(attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]);
}

/// OBJ's vt lines (u and v; a third value is ignored). Values are kept as written: the texture lookup wraps them
/// and reads non-finite ones as 0.
void gather_texcoords(const tinyobj::attrib_t& attrib, Scene& scene) {
  const size_t count = attrib.texcoords.size() / 2;
  scene.texcoords.reserve(count);
  for (size_t i = 0; i < count; ++i) scene.texcoords.emplace_back(attrib.texcoords[2 * i], attrib.texcoords[2 * i + 1]);
}

/// File normals, normalised (those already of unit length kept bit for bit); unusable ones (zero, NaN, overflow)
/// leave their corners on the geometric normal. Returns, per file normal, its index in scene.normals or kNoNormal.
std::vector<uint32_t> gather_normals(const tinyobj::attrib_t& attrib, const std::string& label, Scene& scene,
                                     std::vector<std::string>& warnings) {
  const size_t normal_count = attrib.normals.size() / 3;
  std::vector<uint32_t> normal_remap(normal_count, kNoNormal);
  size_t unusable_normals = 0;
  for (size_t i = 0; i < normal_count; ++i) {
    const Vec3 n(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
    const float length = glm::length(n);
    if (length > 0.0f && std::isfinite(length) && is_finite(n / length)) {
      normal_remap[i] = static_cast<uint32_t>(scene.normals.size());
      // A normal of unit length up to float rounding is kept as written: dividing by its length would move its last
      // bits, and a scene written out (--export-scene) would not read back as the same scene.
      const bool unit = std::abs(length - 1.0f) <= 4.0f * std::numeric_limits<float>::epsilon();
      scene.normals.push_back(unit ? n : n / length);
    } else {
      ++unusable_normals;
    }
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

/// Appends the triangles of every shape in file order, with their normals and materials. Faces that tinyobjloader
/// could not triangulate (fewer than 3 corners left) are skipped.
void gather_triangles(const tinyobj::ObjReader& reader, const std::vector<uint32_t>& normal_remap,
                      const std::string& label, MaterialTable& materials, Scene& scene) {
  const size_t vertex_count = reader.GetAttrib().vertices.size() / 3;
  const size_t normal_count = normal_remap.size();
  const size_t texcoord_count = scene.texcoords.size();
  auto checked_index = [&](int index, size_t count) -> uint32_t {
    // The validator makes this unreachable; it guards against tinyobjloader disagreeing with it.
    if (index < 0 || static_cast<size_t>(index) >= count)
      throw SceneError(label + ": face refers to a missing vertex (index " + std::to_string(index) + ")");
    return static_cast<uint32_t>(index);
  };
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t corners = mesh.num_face_vertices[f];
      if (corners == 3 && offset + 3 <= mesh.indices.size()) {
        Triangle tri;
        for (size_t c = 0; c < 3; ++c) {
          const tinyobj::index_t& index = mesh.indices[offset + c];
          tri.v[c] = checked_index(index.vertex_index, vertex_count);
          if (index.normal_index >= 0) tri.n[c] = normal_remap[checked_index(index.normal_index, normal_count)];
          if (index.texcoord_index >= 0) tri.t[c] = checked_index(index.texcoord_index, texcoord_count);
        }
        const int id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
        const int64_t mapped = id >= 0 && static_cast<size_t>(id) < materials.remap.size() ? materials.remap[id] : -1;
        tri.material = mapped >= 0 ? static_cast<uint32_t>(mapped) : default_material_index(materials, scene);
        scene.triangles.push_back(tri);
      }
      offset += corners;
    }
  }
}

/// A scene needs a triangle; fewer triangles than the faces promised is worth a warning.
void check_triangle_count(const Scene& scene, const ObjSummary& summary, const std::string& label,
                          std::vector<std::string>& warnings) {
  if (scene.triangles.empty()) {
    if (summary.expected_triangles > 0)
      throw SceneError(label + ": no triangles: triangulating its faces gave none (degenerate polygons)");
    throw SceneError(label + ": no triangles");
  }
  if (scene.triangles.size() < summary.expected_triangles) {
    warnings.push_back(label + ": " + counted(summary.expected_triangles - scene.triangles.size(), "triangle") +
                       " of polygons lost in triangulation");
  }
}

/// Says why faces ended up grey: no materials at all, faces before the first usemtl, or unknown material names
/// (the first five by line, then a count).
void explain_default_material(const MaterialTable& materials, const ObjSummary& summary, const std::string& label,
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
void assign_shading_normals(const ObjSummary& summary, const LoadOptions& options, Scene& scene) {
  if (summary.references_normals) return;
  if (options.smooth_normals) {
    compute_smooth_normals(scene, options.crease_degrees);
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
  const std::optional<Enclosure> room = find_enclosure(scene.bounds(), brute_force_ray_cast(scene));
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

LoadedScene build_scene(const std::string& obj_text, const std::string& label, const std::string& scene_name,
                        ObjSummary& summary, const std::vector<MtlSource>& mtl_sources, const LoadOptions& options) {
  LoadedScene result;
  std::vector<std::string>& warnings = result.warnings;
  warnings = std::move(summary.warnings);

  const MtlStream mtl = merge_mtl_sources(mtl_sources, warnings);
  const tinyobj::ObjReader reader = parse_obj(obj_text, mtl.text, label);
  relabel_parser_warnings(reader.Warning(), label, mtl_sources, warnings);

  Scene& scene = result.scene;
  scene.name = scene_name;
  gather_positions(reader.GetAttrib(), scene);
  const std::vector<uint32_t> normal_remap = gather_normals(reader.GetAttrib(), label, scene, warnings);
  gather_texcoords(reader.GetAttrib(), scene);
  MaterialTable materials = gather_materials(reader.GetMaterials(), mtl.entries, scene);
  gather_triangles(reader, normal_remap, label, materials, scene);

  check_triangle_count(scene, summary, label, warnings);
  explain_default_material(materials, summary, label, warnings);
  report_degenerate_triangles(scene, label, warnings);
  assign_shading_normals(summary, options, scene);
  ensure_emitter(label, options, scene, warnings);
  return result;
}

}  // namespace lueur::obj
