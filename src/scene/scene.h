// The flat scene every other layer reads: positions, shading normals, triangles, materials and the emitter list.
// Plain data with indices instead of pointers. Depends on core only.
#pragma once

#include <string>
#include <vector>

#include "core/ray.h"

namespace lueur {

/// An OBJ/MTL material reduced to what the Blinn-Phong passes need.
struct Material {
  std::string name = "default";
  Vec3 kd{0.5f};    ///< diffuse albedo
  Vec3 ks{0.0f};    ///< specular albedo; zero selects the report's Blinn-Phong mix with K
  float ns = 0.0f;  ///< Blinn-Phong exponent
  Vec3 ke{0.0f};    ///< emitted radiance; any positive channel makes the material an area light

  bool emissive() const { return ke.r > 0.0f || ke.g > 0.0f || ke.b > 0.0f; }
  bool has_specular() const { return ks.r > 0.0f || ks.g > 0.0f || ks.b > 0.0f; }
};

inline constexpr uint32_t kNoNormal = 0xffffffffu;

/// One triangle: three position indices, three shading-normal indices (kNoNormal: use the geometric normal)
/// and a material index. Counter-clockwise winding defines the geometric normal and the emitting side.
struct Triangle {
  uint32_t v[3] = {0, 0, 0};
  uint32_t n[3] = {kNoNormal, kNoNormal, kNoNormal};
  uint32_t material = 0;
};

struct Scene {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  ///< unit shading normals, referenced by Triangle::n
  std::vector<Triangle> triangles;
  std::vector<Material> materials;
  std::vector<uint32_t> emitters;  ///< indices of triangles whose material emits and whose area is positive
  std::string name;                ///< shown in messages and saved with images

  Box3 bounds() const;
  /// Unnormalised geometric normal (e1 x e2): its length is twice the area.
  Vec3 geometric_normal_raw(uint32_t tri) const;
  float area(uint32_t tri) const { return 0.5f * glm::length(geometric_normal_raw(tri)); }
  const Material& material_of(uint32_t tri) const { return materials[triangles[tri].material]; }
  /// Shading normal at barycentrics (u, v); falls back to the geometric normal.
  Vec3 shading_normal(uint32_t tri, float u, float v) const;
  Vec3 point(uint32_t tri, float u, float v) const;
};

/// Appends a planar quad a b c d as two triangles (a b c) and (a c d) with `material`; its geometric normal faces
/// the side from which a b c d run counter-clockwise.
void add_quad(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, uint32_t material);

/// Rebuilds `scene.emitters` from the materials (zero-area emissive triangles are left out).
void collect_emitters(Scene& scene);

/// Replaces the shading normals by smooth ones: each corner averages, weighted by the corner's angle, the face
/// normals of the triangles around the same position whose normals lie within `crease_degrees` of its own.
/// Faces beyond the crease keep a sharp edge (a box stays a box).
void compute_smooth_normals(Scene& scene, float crease_degrees = 60.0f);

/// Drops shading normals: every triangle is shaded with its geometric normal.
void clear_normals(Scene& scene);

/// Adds a grey diffuse quad light above the scene's bounding box, facing down, bright enough that a white
/// surface below it reads about 1. Used when a scene has no emitter.
void add_default_light(Scene& scene);

}  // namespace lueur
