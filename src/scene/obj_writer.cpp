// OBJ + MTL export: positions, shading normals, texture coordinates, faces grouped into runs of one material, and
// Kd/Ks/Ns/Ke materials (and a mirror's or glass's illum, Ni and Tf) with their texture maps.
// Depends on core (atomic writes) and scene only; never on tinyobjloader, GL or the render passes.
#include "scene/obj_writer.h"

#include "core/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <string_view>
#include <unordered_set>

namespace lueur {
namespace {

void append_format(std::string& out, const char* format, float a, float b, float c) {
  char buffer[128];
  const int n = std::snprintf(buffer, sizeof buffer, format, static_cast<double>(a), static_cast<double>(b),
                              static_cast<double>(c));
  out.append(buffer, static_cast<size_t>(n));
}

/// A material name that survives `newmtl`/`usemtl`: no blanks or control bytes (usemtl stops at a blank),
/// not empty, and unique (usemtl of a duplicate would resolve to the first one).
std::vector<std::string> usable_names(const std::vector<Material>& materials) {
  std::vector<std::string> names;
  std::unordered_set<std::string> taken;
  for (const Material& m : materials) {
    std::string name = m.name;
    for (char& c : name) {
      if (static_cast<unsigned char>(c) <= 0x20 || c == 0x7f) c = '_';
    }
    if (name.empty()) name = "material";
    const std::string base = name;
    for (int suffix = 2; taken.count(name); ++suffix) name = base + "_" + std::to_string(suffix);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

/// Whether all three corners of a triangle carry an index (a face in OBJ gives one to every corner or to none).
bool all_given(const uint32_t (&indices)[3], uint32_t none) {
  return indices[0] != none && indices[1] != none && indices[2] != none;
}

/// One corner of a face: "v", "v/t", "v//n" or "v/t/n", indices from 1.
void append_corner(std::string& out, uint32_t v, uint32_t t, uint32_t n, bool with_t, bool with_n) {
  out += ' ';
  out += std::to_string(v + 1);
  if (!with_t && !with_n) return;
  out += '/';
  if (with_t) out += std::to_string(t + 1);
  if (with_n) {
    out += '/';
    out += std::to_string(n + 1);
  }
}

}  // namespace

void write_obj(const Scene& scene, const std::string& obj_path) {
  namespace fs = std::filesystem;
  fs::path mtl_path = fs::path(obj_path).replace_extension(".mtl");
  if (mtl_path == fs::path(obj_path)) mtl_path = fs::path(obj_path + ".mtl");  // writing an OBJ named *.mtl
  const std::string mtl_name = mtl_path.filename().string();
  const std::vector<std::string> names = usable_names(scene.materials);

  std::string mtl = "# Lueur scene '" + scene.name + "'\n";
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    mtl += "\nnewmtl " + names[i] + "\n";
    append_format(mtl, "Kd %.9g %.9g %.9g\n", m.kd.r, m.kd.g, m.kd.b);
    append_format(mtl, "Ks %.9g %.9g %.9g\n", m.ks.r, m.ks.g, m.ks.b);
    char buffer[64];
    const int n = std::snprintf(buffer, sizeof buffer, "Ns %.9g\n", static_cast<double>(m.ns));
    mtl.append(buffer, static_cast<size_t>(n));
    append_format(mtl, "Ke %.9g %.9g %.9g\n", m.ke.r, m.ke.g, m.ke.b);
    // A mirror or glass as the models that read back as one (illum 5 and 7); the BRDF's default (2) is not written.
    if (m.surface == SurfaceKind::kMirror) mtl += "illum 5\n";
    if (m.surface == SurfaceKind::kGlass) {
      mtl += "illum 7\n";
      const int length = std::snprintf(buffer, sizeof buffer, "Ni %.9g\n", static_cast<double>(m.ior));
      mtl.append(buffer, static_cast<size_t>(length));
      append_format(mtl, "Tf %.9g %.9g %.9g\n", m.tf.r, m.tf.g, m.tf.b);
    }
    // The maps as the scene's MTL named them: relative to its folder, so they are found when the export lies there.
    if (!m.diffuse_map.empty()) mtl += "map_Kd " + m.diffuse_map + "\n";
    if (!m.alpha_map.empty()) mtl += "map_d " + m.alpha_map + "\n";
  }

  std::string obj;
  obj.reserve(scene.positions.size() * 40 + scene.triangles.size() * 24 + 256);
  obj += "# Lueur scene '" + scene.name + "'\n";
  // tinyobjloader splits mtllib names at blanks; a backslash keeps a blank inside one name.
  std::string escaped;
  for (char c : mtl_name) {
    if (c == ' ') escaped += '\\';
    escaped += c;
  }
  obj += "mtllib " + escaped + "\n";
  for (const Vec3& p : scene.positions) append_format(obj, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
  for (const Vec3& n : scene.normals) append_format(obj, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
  for (const Vec2& t : scene.texcoords) {
    char buffer[64];
    const int n = std::snprintf(buffer, sizeof buffer, "vt %.9g %.9g\n", static_cast<double>(t.x),
                                static_cast<double>(t.y));
    obj.append(buffer, static_cast<size_t>(n));
  }

  uint32_t current = 0xffffffffu;
  for (const Triangle& t : scene.triangles) {
    if (t.material != current && t.material < names.size()) {
      current = t.material;
      obj += "usemtl " + names[current] + "\n";
    }
    const bool with_t = all_given(t.t, kNoTexcoord), with_n = all_given(t.n, kNoNormal);
    obj += 'f';
    for (int k = 0; k < 3; ++k) append_corner(obj, t.v[k], t.t[k], t.n[k], with_t, with_n);
    obj += '\n';
  }

  // The MTL goes first so that a reader never sees an OBJ whose material file does not exist yet.
  write_file_atomically(mtl_path.string(), mtl);
  write_file_atomically(obj_path, obj);
}

}  // namespace lueur
