// Builds the default scene in code. The Cornell box coordinates are the published measurements of the
// Cornell Program of Computer Graphics; the apple and the wall lamp are Lueur's own procedural geometry.
#include "scene/default_scene.h"

#include <array>
#include <cmath>

namespace lueur {
namespace {

struct SceneBuilder {
  Scene& scene;

  uint32_t add_material(const Material& m) {
    scene.materials.push_back(m);
    return static_cast<uint32_t>(scene.materials.size() - 1);
  }
  uint32_t add_vertex(const Vec3& p) {
    scene.positions.push_back(p);
    return static_cast<uint32_t>(scene.positions.size() - 1);
  }
  void add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
    Triangle t;
    t.v[0] = a;
    t.v[1] = b;
    t.v[2] = c;
    t.material = material;
    scene.triangles.push_back(t);
  }
  /// A planar quad given counter-clockwise as seen from the side it faces, as two triangles (0 1 2, 0 2 3).
  void add_quad(const std::array<Vec3, 4>& q, uint32_t material) {
    lueur::add_quad(scene, q[0], q[1], q[2], q[3], material);
  }
  /// A block: the top quad (counter-clockwise seen from above) extruded down to the floor; the bottom is hidden.
  void add_block(const std::array<Vec3, 4>& top, uint32_t material) {
    add_quad(top, material);
    for (int i = 0; i < 4; ++i) {
      const Vec3 a = top[static_cast<size_t>(i)], b = top[static_cast<size_t>((i + 1) % 4)];
      // Walking the top counter-clockwise from above, the outward side quad is b, a, a-floor, b-floor.
      add_quad({b, a, Vec3(a.x, 0.0f, a.z), Vec3(b.x, 0.0f, b.z)}, material);
    }
  }
};

Material make_material(const char* name, Vec3 kd, Vec3 ks = Vec3(0.0f), float ns = 0.0f, Vec3 ke = Vec3(0.0f)) {
  Material m;
  m.name = name;
  m.kd = kd;
  m.ks = ks;
  m.ns = ns;
  m.ke = ke;
  return m;
}

/// Apple profile: radius and height at polar angle theta (0 at the stem), with dimples at both poles.
Vec2 apple_profile(float theta, float radius) {
  const float dimple =
      1.0f - 0.28f * std::exp(-theta * theta / 0.25f) - 0.12f * std::exp(-(kPi - theta) * (kPi - theta) / 0.3f);
  const float r = radius * dimple;
  return Vec2(r * std::sin(theta), 0.88f * r * std::cos(theta));
}

/// A low-poly apple standing on `base` (the centre of its resting plane): rings x segments quads, fans at the
/// poles, and a short tilted stem. A few hundred triangles: coarse enough that smooth normals visibly matter.
void add_apple(SceneBuilder& b, Vec3 base, float radius, uint32_t skin, uint32_t stem) {
  constexpr int kSegments = 16;
  constexpr int kRings = 12;
  // The lowest point of the profile sets how far the apple must be lifted to rest on the base.
  float lowest = 0.0f;
  for (int r = 0; r <= kRings; ++r) lowest = std::min(lowest, apple_profile(kPi * r / kRings, radius).y);
  const Vec3 centre = base + Vec3(0.0f, -lowest, 0.0f);

  auto ring_vertex = [&](int ring, int segment) {
    const Vec2 rp = apple_profile(kPi * static_cast<float>(ring) / kRings, radius);
    const float phi = 2.0f * kPi * static_cast<float>(segment % kSegments) / kSegments;
    return centre + Vec3(rp.x * std::cos(phi), rp.y, rp.x * std::sin(phi));
  };
  const uint32_t top = b.add_vertex(ring_vertex(0, 0));
  std::vector<uint32_t> rings;  // rings 1 .. kRings-1, kSegments vertices each
  for (int r = 1; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) rings.push_back(b.add_vertex(ring_vertex(r, s)));
  const uint32_t bottom = b.add_vertex(ring_vertex(kRings, 0));
  auto at = [&](int r, int s) { return rings[static_cast<size_t>((r - 1) * kSegments + (s % kSegments))]; };

  // Outward-facing, counter-clockwise seen from outside: phi grows from +x towards +z.
  for (int s = 0; s < kSegments; ++s) b.add_triangle(top, at(1, s + 1), at(1, s), skin);
  for (int r = 1; r < kRings - 1; ++r)
    for (int s = 0; s < kSegments; ++s) {
      b.add_triangle(at(r, s), at(r, s + 1), at(r + 1, s + 1), skin);
      b.add_triangle(at(r, s), at(r + 1, s + 1), at(r + 1, s), skin);
    }
  for (int s = 0; s < kSegments; ++s) b.add_triangle(bottom, at(kRings - 1, s), at(kRings - 1, s + 1), skin);

  // The stem: a thin hexagonal prism leaning a little, from inside the dimple upward, with a cap.
  constexpr int kStemSides = 6;
  const Vec3 stem_base = b.scene.positions[top] - Vec3(0.0f, 0.05f * radius, 0.0f);
  const Vec3 stem_tip = stem_base + Vec3(0.12f * radius, 0.42f * radius, 0.05f * radius);
  const float stem_radius = 0.06f * radius;
  std::array<uint32_t, kStemSides> lower{}, upper{};
  for (int i = 0; i < kStemSides; ++i) {
    const float phi = 2.0f * kPi * static_cast<float>(i) / kStemSides;
    const Vec3 offset(stem_radius * std::cos(phi), 0.0f, stem_radius * std::sin(phi));
    lower[static_cast<size_t>(i)] = b.add_vertex(stem_base + offset);
    upper[static_cast<size_t>(i)] = b.add_vertex(stem_tip + 0.7f * offset);
  }
  const uint32_t cap = b.add_vertex(stem_tip + Vec3(0.0f, 0.01f * radius, 0.0f));
  for (int i = 0; i < kStemSides; ++i) {
    const size_t j = static_cast<size_t>(i), k = static_cast<size_t>((i + 1) % kStemSides);
    b.add_triangle(lower[j], upper[k], upper[j], stem);
    b.add_triangle(lower[j], lower[k], upper[k], stem);
    b.add_triangle(cap, upper[j], upper[k], stem);
  }
}

/// A small square lamp on the back wall facing the room (-z), cut into cells x cells quads.
void add_wall_lamp(SceneBuilder& b, Vec3 centre, float side, int cells, uint32_t material) {
  const float h = 0.5f * side, step = side / static_cast<float>(cells);
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const float x0 = centre.x - h + step * static_cast<float>(i), x1 = x0 + step;
      const float y0 = centre.y - h + step * static_cast<float>(j), y1 = y0 + step;
      // Facing -z: counter-clockwise seen from the camera side (+x is to the viewer's left).
      b.add_quad({Vec3(x1, y0, centre.z), Vec3(x0, y0, centre.z), Vec3(x0, y1, centre.z), Vec3(x1, y1, centre.z)},
                 material);
    }
}

}  // namespace

Scene make_default_scene() {
  Scene scene;
  scene.name = "cornell-apple";
  SceneBuilder b{scene};

  // Reflectances: the usual RGB fits of the measured Cornell spectra.
  const uint32_t white = b.add_material(make_material("white", Vec3(0.725f, 0.71f, 0.68f)));
  const uint32_t red = b.add_material(make_material("red", Vec3(0.63f, 0.065f, 0.05f)));
  const uint32_t green = b.add_material(make_material("green", Vec3(0.14f, 0.45f, 0.091f)));
  const uint32_t ceiling_light =
      b.add_material(make_material("ceiling-light", Vec3(0.78f), Vec3(0.0f), 0.0f, Vec3(34.0f, 24.0f, 8.0f)));
  const uint32_t wall_lamp =
      b.add_material(make_material("wall-lamp", Vec3(0.78f), Vec3(0.0f), 0.0f, Vec3(10.0f, 18.0f, 40.0f)));
  const uint32_t skin = b.add_material(make_material("apple-skin", Vec3(0.62f, 0.05f, 0.04f), Vec3(0.25f), 48.0f));
  const uint32_t stem = b.add_material(make_material("apple-stem", Vec3(0.25f, 0.15f, 0.06f)));

  // Cornell box, published measurements (mm).
  b.add_quad({Vec3(552.8f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 0.0f, 559.2f), Vec3(549.6f, 0.0f, 559.2f)},
             white);  // floor
  b.add_quad(
      {Vec3(556.0f, 548.8f, 0.0f), Vec3(556.0f, 548.8f, 559.2f), Vec3(0.0f, 548.8f, 559.2f), Vec3(0.0f, 548.8f, 0.0f)},
      white);  // ceiling
  b.add_quad(
      {Vec3(549.6f, 0.0f, 559.2f), Vec3(0.0f, 0.0f, 559.2f), Vec3(0.0f, 548.8f, 559.2f), Vec3(556.0f, 548.8f, 559.2f)},
      white);  // back wall
  b.add_quad({Vec3(0.0f, 0.0f, 559.2f), Vec3(0.0f, 0.0f, 0.0f), Vec3(0.0f, 548.8f, 0.0f), Vec3(0.0f, 548.8f, 559.2f)},
             green);  // right wall
  b.add_quad(
      {Vec3(552.8f, 0.0f, 0.0f), Vec3(549.6f, 0.0f, 559.2f), Vec3(556.0f, 548.8f, 559.2f), Vec3(556.0f, 548.8f, 0.0f)},
      red);  // left wall
  // The ceiling light, lowered 0.5 mm below the ceiling so that the two never share a plane.
  b.add_quad({Vec3(343.0f, 548.3f, 227.0f), Vec3(343.0f, 548.3f, 332.0f), Vec3(213.0f, 548.3f, 332.0f),
              Vec3(213.0f, 548.3f, 227.0f)},
             ceiling_light);
  b.add_block({Vec3(130.0f, 165.0f, 65.0f), Vec3(82.0f, 165.0f, 225.0f), Vec3(240.0f, 165.0f, 272.0f),
               Vec3(290.0f, 165.0f, 114.0f)},
              white);  // short block
  b.add_block({Vec3(423.0f, 330.0f, 247.0f), Vec3(265.0f, 330.0f, 296.0f), Vec3(314.0f, 330.0f, 456.0f),
               Vec3(472.0f, 330.0f, 406.0f)},
              white);  // tall block

  // A small blue lamp high on the back wall, above the short block, 0.5 mm in front of the wall: 128 triangles
  // of 78 mm^2 each against the ceiling light's two of 6825 mm^2.
  add_wall_lamp(b, Vec3(150.0f, 430.0f, 558.7f), 100.0f, 8, wall_lamp);
  // The apple on the short block's top (centre of its four corners).
  add_apple(b, Vec3(185.5f, 165.0f, 169.0f), 42.0f, skin, stem);

  collect_emitters(scene);
  return scene;
}

}  // namespace lueur
