// The flat scene every other layer reads: positions, shading normals, triangles, materials and the emitter list.
// Plain data with indices instead of pointers. Depends on core only.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/ray.h"
#include "scene/texture.h"

namespace lueur {

/// How a material scatters light, from the MTL's `illum`: today's BRDF (Lambert / Blinn-Phong / the report's mix;
/// illum 0-2 and 8-10), a perfect mirror of reflectance Ks (illum 3 and 5), or smooth glass of index Ni whose
/// transmitted light Tf tints (illum 4, 6 and 7). The mirror and the glass may have a Lambert base of albedo Kd
/// (integrator/specular.h shares the reflectance out so that the sum never exceeds 1).
enum class SurfaceKind : uint8_t { kBrdf = 0, kMirror = 1, kGlass = 2 };

/// An OBJ/MTL material reduced to what the passes need.
struct Material {
  std::string name = "default";
  Vec3 kd{0.5f};    ///< diffuse albedo
  Vec3 ks{0.0f};    ///< specular albedo; zero selects the report's Blinn-Phong mix with K
  float ns = 0.0f;  ///< Blinn-Phong exponent
  Vec3 ke{0.0f};    ///< emitted radiance; any positive channel makes the material an area light
  SurfaceKind surface = SurfaceKind::kBrdf;
  float ior = 1.5f;  ///< glass: the index of refraction (Ni) inside, against 1 outside (the side the winding faces)
  Vec3 tf{1.0f};     ///< glass: the transmission filter (Tf) that tints the light passing through
  /// Index in Scene::textures of the colour map that replaces kd (map_Kd), or -1.
  int32_t diffuse_texture = -1;
  /// Index in Scene::textures of the cutout mask (map_d): where it covers less than half, the surface is a hole.
  int32_t alpha_texture = -1;
  std::string diffuse_map, alpha_map;  ///< the MTL's map_Kd and map_d file names, as written ("" when absent)

  bool emissive() const { return ke.r > 0.0f || ke.g > 0.0f || ke.b > 0.0f; }
  /// Whether the BRDF has a Blinn-Phong lobe of albedo Ks (a mirror's Ks is its reflectance instead).
  bool has_specular() const { return surface == SurfaceKind::kBrdf && (ks.r > 0.0f || ks.g > 0.0f || ks.b > 0.0f); }
  /// Whether rays meeting it continue along a perfectly specular direction: a mirror or glass.
  bool is_specular() const { return surface != SurfaceKind::kBrdf; }
};

inline constexpr uint32_t kNoNormal = 0xffffffffu;
inline constexpr uint32_t kNoTexcoord = 0xffffffffu;

/// One triangle: three position indices, three shading-normal indices (kNoNormal: use the geometric normal)
/// and a material index. Counter-clockwise winding defines the geometric normal and the emitting side.
struct Triangle {
  uint32_t v[3] = {0, 0, 0};
  uint32_t n[3] = {kNoNormal, kNoNormal, kNoNormal};
  uint32_t t[3] = {kNoTexcoord, kNoTexcoord, kNoTexcoord};  ///< texture coordinates, referenced by index
  uint32_t material = 0;
};

struct Scene {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< unit shading normals, referenced by Triangle::n
  std::vector<Triangle> triangles;
  std::vector<Material> materials;
  std::vector<Vec2> texcoords;     ///< OBJ's vt, referenced by Triangle::t
  std::vector<Texture> textures;   ///< referenced by Material::diffuse_texture and alpha_texture
  std::vector<uint32_t> emitters;  ///< indices of triangles whose material emits and whose area is positive
  std::string name;                ///< shown in messages and saved with images
  /// Triangles from this index on are the default light rig (add_light_rig), not the model: bounds() leaves them out.
  uint32_t rig_begin = kNoRig;
  static constexpr uint32_t kNoRig = 0xffffffffu;

  /// The model's bounding box: its triangles' corners, the light rig's left out.
  Box3 bounds() const;
  /// Unnormalised geometric normal (e1 x e2): its length is twice the area.
  Vec3 geometric_normal_raw(uint32_t tri) const;
  float area(uint32_t tri) const { return 0.5f * glm::length(geometric_normal_raw(tri)); }
  const Material& material_of(uint32_t tri) const { return materials[triangles[tri].material]; }
  /// Shading normal at barycentrics (u, v); falls back to the geometric normal.
  Vec3 shading_normal(uint32_t tri, float u, float v) const;
  Vec3 point(uint32_t tri, float u, float v) const;
  /// Texture coordinate at barycentrics (u, v); (0, 0) on a triangle without them.
  Vec2 texcoord(uint32_t tri, float u, float v) const;
  /// Diffuse albedo at barycentrics (u, v): the colour map where the material has one, else Kd.
  Vec3 albedo(uint32_t tri, float u, float v) const {
    const Material& m = material_of(tri);
    if (m.diffuse_texture < 0) return m.kd;
    return sample_albedo(textures[static_cast<size_t>(m.diffuse_texture)], texcoord(tri, u, v));
  }
  /// Whether the point at barycentrics (u, v) is a hole of its material's cutout mask: no ray stops there.
  bool cut_out(uint32_t tri, float u, float v) const {
    const Material& m = material_of(tri);
    if (m.alpha_texture < 0) return false;
    return sample_coverage(textures[static_cast<size_t>(m.alpha_texture)], texcoord(tri, u, v)) < 0.5f;
  }
  /// Whether any material has a cutout mask (the accelerators then filter their hits through cut_out).
  bool has_cutouts() const;
  /// Bytes the decoded textures hold.
  uint64_t texture_bytes() const;
};

/// Appends a planar quad a b c d as two triangles (a b c) and (a c d) with `material`; its geometric normal faces
/// the side from which a b c d run counter-clockwise.
void add_quad(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, uint32_t material);

/// Rebuilds `scene.emitters` from the materials (zero-area emissive triangles are left out).
void collect_emitters(Scene& scene);

/// Replaces the shading normals by smooth ones: each corner averages, weighted by the corner's angle, the face
/// normals of the triangles around the same position whose normals lie within `crease_degrees` of its own.
/// Faces beyond the crease keep a sharp edge (a box stays a box). Runs on `threads` threads (0: every core); the
/// result is the same whatever their number. `progress`, when given, is told the share done, from the calling thread.
void compute_smooth_normals(Scene& scene, float crease_degrees = 60.0f, unsigned threads = 0,
                            const std::function<void(double done)>& progress = {});

/// Drops shading normals: every triangle is shaded with its geometric normal.
void clear_normals(Scene& scene);

/// Adds a grey diffuse quad light above the scene's bounding box, facing down, bright enough that a white
/// surface below it reads about 1. Used when a scene has no emitter.
void add_default_light(Scene& scene);

}  // namespace lueur
