// Scene queries (bounds, normals, points), emitter collection, smooth-normal generation and the default light.
// Depends on core only: never on GL, the BVH or the render passes.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

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

namespace {

// Bit-exact key for deduplicating normals; -0 is folded into +0 first so equal values share one entry.
struct Vec3Key {
  uint32_t bits[3];
  bool operator==(const Vec3Key& other) const {
    return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
  }
};

Vec3Key key_of(const Vec3& v) {
  Vec3Key key{};
  for (int i = 0; i < 3; ++i) {
    const float value = v[i] + 0.0f;
    std::memcpy(&key.bits[i], &value, sizeof value);
  }
  return key;
}

struct Vec3KeyHash {
  size_t operator()(const Vec3Key& key) const {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (uint32_t b : key.bits) h = (h ^ b) * 0x100000001b3ull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

bool less_xyz(const Vec3& a, const Vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Gives every position the id of its group of exactly equal positions, so that triangle soups (each triangle
// with its own copies of the corners) smooth like indexed meshes.
std::vector<uint32_t> weld_positions(const std::vector<Vec3>& positions) {
  std::vector<uint32_t> weld(positions.size());
  std::vector<uint32_t> order;
  order.reserve(positions.size());
  uint32_t next_id = 0;
  for (uint32_t i = 0; i < positions.size(); ++i) {
    // NaN would break the strict weak ordering of the sort; such points simply stay alone.
    if (is_finite(positions[i])) {
      order.push_back(i);
    } else {
      weld[i] = next_id++;
    }
  }
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return less_xyz(positions[a], positions[b]); });
  for (size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || less_xyz(positions[order[k - 1]], positions[order[k]])) ++next_id;
    weld[order[k]] = next_id - 1;
  }
  return weld;
}

float corner_angle(const Vec3& at, const Vec3& a, const Vec3& b) {
  const Vec3 e1 = a - at;
  const Vec3 e2 = b - at;
  // atan2 of |cross| and dot stays accurate for the very small and very flat angles where acos does not.
  return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
}

}  // namespace

void compute_smooth_normals(Scene& scene, float crease_degrees) {
  const size_t triangle_count = scene.triangles.size();
  const float crease = std::clamp(std::isfinite(crease_degrees) ? crease_degrees : 60.0f, 0.0f, 180.0f);
  // The small slack lets faces with the same normal (dot rounding to just under 1) join even at crease 0.
  const float cos_crease = std::cos(crease * kPi / 180.0f) - 1e-6f;

  // Unit face normals; zero-area (or overflowing) triangles have none and take no part.
  std::vector<Vec3> face_normal(triangle_count, Vec3(0.0f));
  std::vector<uint8_t> usable(triangle_count, 0);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    const Vec3 raw = scene.geometric_normal_raw(t);
    const float length = glm::length(raw);
    if (length > 0.0f && std::isfinite(length)) {
      face_normal[t] = raw / length;
      usable[t] = 1;
    }
  }

  // Corners grouped by welded position (compressed rows: corners of group g lie in [start[g], start[g+1])).
  const std::vector<uint32_t> weld = weld_positions(scene.positions);
  const uint32_t group_count = weld.empty() ? 0u : *std::max_element(weld.begin(), weld.end()) + 1u;
  std::vector<uint32_t> start(group_count + 1, 0);
  for (uint32_t t = 0; t < triangle_count; ++t) {
    if (!usable[t]) continue;
    for (uint32_t c = 0; c < 3; ++c) ++start[weld[scene.triangles[t].v[c]] + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<uint32_t> corners(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t t = 0; t < triangle_count; ++t) {
      if (!usable[t]) continue;
      for (uint32_t c = 0; c < 3; ++c) corners[fill[weld[scene.triangles[t].v[c]]]++] = 3 * t + c;
    }
  }

  std::vector<Triangle>& triangles = scene.triangles;
  std::vector<Vec3> normals;
  std::unordered_map<Vec3Key, uint32_t, Vec3KeyHash> normal_index;
  auto intern = [&](const Vec3& n) {
    const auto [it, inserted] = normal_index.try_emplace(key_of(n), static_cast<uint32_t>(normals.size()));
    if (inserted) normals.push_back(n);
    return it->second;
  };

  for (Triangle& tri : triangles) tri.n[0] = tri.n[1] = tri.n[2] = kNoNormal;

  // Per group, corners whose faces share one normal get one result: a flat fan around a vertex of a
  // 5000-gon costs one sum, not 5000 x 5000.
  struct Distinct {
    Vec3 normal;
    float weight;
    Vec3 smooth;
  };
  std::vector<Distinct> distinct;
  std::vector<uint32_t> order;
  for (uint32_t g = 0; g < group_count; ++g) {
    const uint32_t begin = start[g];
    const uint32_t end = start[g + 1];
    if (begin == end) continue;
    order.assign(corners.begin() + begin, corners.begin() + end);
    std::sort(order.begin(), order.end(),
              [&](uint32_t a, uint32_t b) { return less_xyz(face_normal[a / 3], face_normal[b / 3]); });
    distinct.clear();
    for (uint32_t corner : order) {
      const uint32_t t = corner / 3;
      const uint32_t c = corner % 3;
      const Triangle& tri = triangles[t];
      const float angle = corner_angle(scene.positions[tri.v[c]], scene.positions[tri.v[(c + 1) % 3]],
                                       scene.positions[tri.v[(c + 2) % 3]]);
      if (distinct.empty() || less_xyz(distinct.back().normal, face_normal[t])) {
        distinct.push_back({face_normal[t], 0.0f, Vec3(0.0f)});
      }
      distinct.back().weight += std::isfinite(angle) ? angle : 0.0f;
    }
    for (Distinct& d : distinct) {
      Vec3 sum(0.0f);
      for (const Distinct& other : distinct) {
        if (glm::dot(d.normal, other.normal) >= cos_crease) sum += other.weight * other.normal;
      }
      const float length = glm::length(sum);
      d.smooth = (length > 1e-12f && std::isfinite(length)) ? sum / length : d.normal;
    }
    size_t k = 0;
    for (uint32_t corner : order) {
      const Vec3& n = face_normal[corner / 3];
      while (less_xyz(distinct[k].normal, n)) ++k;
      triangles[corner / 3].n[corner % 3] = intern(distinct[k].smooth);
    }
  }
  scene.normals = std::move(normals);
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
