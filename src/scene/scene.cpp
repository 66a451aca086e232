// Scene queries (bounds, normals, points), emitter collection and the default light (smooth normals:
// smooth_normals.cpp). Depends on core only: never on GL, the BVH or the render passes.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>

namespace lueur {

Box3 Scene::bounds() const {
  // Walks the triangles rather than `positions` so that stray unreferenced vertices do not widen the box
  // that the camera frames and the default light is placed over.
  Box3 box;
  const size_t model = std::min<size_t>(triangles.size(), rig_begin);
  for (size_t t = 0; t < model; ++t) {
    for (uint32_t corner = 0; corner < 3; ++corner) box.expand(positions[triangles[t].v[corner]]);
  }
  return box;
}

Vec3 Scene::geometric_normal_raw(uint32_t tri) const {
  const Triangle& t = triangles[tri];
  const Vec3& p0 = positions[t.v[0]];
  return glm::cross(positions[t.v[1]] - p0, positions[t.v[2]] - p0);
}

Vec3 Scene::shading_normal(uint32_t tri, float u, float v) const {
  const Triangle& t = triangles[tri];
  if (t.n[0] != kNoNormal && t.n[1] != kNoNormal && t.n[2] != kNoNormal) {
    const Vec3 n = (1.0f - u - v) * normals[t.n[0]] + u * normals[t.n[1]] + v * normals[t.n[2]];
    const float length = glm::length(n);
    // Opposite corner normals can cancel out; a near-zero sum has no usable direction.
    if (length > 1e-6f && std::isfinite(length)) return n / length;
  }
  const Vec3 g = geometric_normal_raw(tri);
  const float length = glm::length(g);
  if (length > 0.0f && std::isfinite(length)) return g / length;
  return Vec3(0.0f, 1.0f, 0.0f);  // zero-area triangle: any unit vector keeps callers free of NaN
}

Vec3 Scene::point(uint32_t tri, float u, float v) const {
  const Triangle& t = triangles[tri];
  return (1.0f - u - v) * positions[t.v[0]] + u * positions[t.v[1]] + v * positions[t.v[2]];
}

Vec2 Scene::texcoord(uint32_t tri, float u, float v) const {
  const Triangle& t = triangles[tri];
  if (t.t[0] == kNoTexcoord || t.t[1] == kNoTexcoord || t.t[2] == kNoTexcoord) return Vec2(0.0f);
  return (1.0f - u - v) * texcoords[t.t[0]] + u * texcoords[t.t[1]] + v * texcoords[t.t[2]];
}

bool Scene::has_cutouts() const {
  for (const Material& m : materials)
    if (m.alpha_texture >= 0) return true;
  return false;
}

uint64_t Scene::texture_bytes() const {
  uint64_t bytes = 0;
  for (const Texture& t : textures) bytes += t.bytes();
  return bytes;
}

void collect_emitters(Scene& scene) {
  scene.emitters.clear();
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    if (!scene.material_of(i).emissive()) continue;
    const float area = scene.area(i);
    if (area > 0.0f && std::isfinite(area)) scene.emitters.push_back(i);
  }
}

void clear_normals(Scene& scene) {
  scene.normals.clear();
  for (Triangle& tri : scene.triangles) tri.n[0] = tri.n[1] = tri.n[2] = kNoNormal;
}

void add_quad(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, uint32_t material) {
  const auto base = static_cast<uint32_t>(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {a, b, c, d});
  Triangle first, second;
  first.v[0] = base, first.v[1] = base + 1, first.v[2] = base + 2, first.material = material;
  second.v[0] = base, second.v[1] = base + 2, second.v[2] = base + 3, second.material = material;
  scene.triangles.push_back(first);
  scene.triangles.push_back(second);
}

void add_default_light(Scene& scene) {
  Box3 box = scene.bounds();
  if (box.empty()) box.expand(Vec3(0.0f));
  // Double precision: extents near the float limit would overflow the squares below.
  const glm::dvec3 lo(box.lo), hi(box.hi);
  const glm::dvec3 center = 0.5 * (lo + hi);
  double size = glm::length(hi - lo);
  // A single point (or coincident points) has no size to scale from; a unit size keeps the light finite.
  if (!(size > 1e-6 * (1.0 + max_abs_component(Vec3(center)))) || !std::isfinite(size)) size = 1.0;
  // Scene::area squares the cross product, whose components are side^2: beyond about 4e9 units it overflows a
  // float and the light would not count as an emitter. Such a scene cannot be traced sensibly anyway, but it
  // still gets a finite light.
  size = std::min(size, 1e9);

  const double height = hi.y + 0.5 * size;
  const double half = 0.25 * size;  // side 0.5 * size
  const float x0 = static_cast<float>(center.x - half), x1 = static_cast<float>(center.x + half);
  const float z0 = static_cast<float>(center.z - half), z1 = static_cast<float>(center.z + half);
  const float y = static_cast<float>(height);

  // Radiance L over area A at distance d gives irradiance E = L A / d^2 straight below; E = pi makes a white
  // Lambertian surface at the box centre reflect radiance E / pi = 1.
  const double area = (2.0 * half) * (2.0 * half);
  // Not height - center.y: far from the origin that difference can round to zero.
  const double distance = 0.5 * (hi.y - lo.y) + 0.5 * size;
  const double radiance = std::min(static_cast<double>(kPi) * distance * distance / area, 1e30);
  Material light;
  light.name = "lueur-default-light";
  light.kd = Vec3(0.0f);
  light.ks = Vec3(0.0f);
  light.ns = 0.0f;
  light.ke = Vec3(static_cast<float>(radiance));
  const uint32_t material = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(light);

  // Counter-clockwise seen from below: the geometric normal is -Y.
  add_quad(scene, Vec3(x0, y, z0), Vec3(x1, y, z0), Vec3(x1, y, z1), Vec3(x0, y, z1), material);
  collect_emitters(scene);  // keeps the emitter list consistent for callers that add the light late
}

}  // namespace lueur
