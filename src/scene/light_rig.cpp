// Closed rooms, the view from inside them, and the default light rig (see light_rig.h).
#include "scene/light_rig.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

namespace lueur {
namespace {

constexpr int kProbeRays = 64;

/// Möller–Trumbore in double: the probe runs once per scene, so precision is worth more than speed here.
bool hit_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b,
                  const glm::dvec3& c, double& t, bool& front) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (!(std::abs(det) > 1e-300)) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  t = glm::dot(e2, q) * inv;
  front = glm::dot(glm::cross(e1, e2), d) < 0.0;
  return t > 0.0;
}

/// `kProbeRays` directions spread evenly over the sphere (a Fibonacci lattice), y up.
std::array<Vec3, kProbeRays> probe_directions() {
  std::array<Vec3, kProbeRays> dirs{};
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kProbeRays; ++i) {
    const double y = 1.0 - (2.0 * i + 1.0) / kProbeRays;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    dirs[static_cast<size_t>(i)] = Vec3(static_cast<float>(r * std::cos(golden * i)), static_cast<float>(y),
                                        static_cast<float>(r * std::sin(golden * i)));
  }
  return dirs;
}

/// Whether `point` lies in a closed room's open space (see find_enclosure).
bool inside_room(const Vec3& point, const RayCast& cast) {
  int hits = 0, front_hits = 0, misses = 0;
  for (const Vec3& dir : probe_directions()) {
    bool front = false;
    if (!std::isfinite(cast(point, dir, front))) {
      if (++misses > 2) return false;  // open: no need to cast the rest
      continue;
    }
    ++hits;
    front_hits += front ? 1 : 0;
  }
  return hits >= kProbeRays - 2 && 2 * front_hits >= hits;
}

/// A grey emitting material of radiance `radiance`, appended; returns its index.
uint32_t add_emitting_material(Scene& scene, const char* name, double radiance) {
  Material light;
  light.name = name;
  light.kd = Vec3(0.0f);
  light.ke = Vec3(static_cast<float>(std::min(radiance, 1e30)));
  scene.materials.push_back(light);
  return static_cast<uint32_t>(scene.materials.size() - 1);
}

/// Model size and centre, kept finite: a single point gets a unit size, and sizes beyond 1e9 are capped so that
/// the rig's areas (side^2) stay inside float.
void rig_frame(const Box3& bounds, glm::dvec3& centre, double& radius) {
  Box3 box = bounds;
  if (box.empty()) box.expand(Vec3(0.0f));
  const glm::dvec3 lo(box.lo), hi(box.hi);
  centre = 0.5 * (lo + hi);
  radius = 0.5 * glm::length(hi - lo);
  if (!(radius > 1e-6 * (1.0 + max_abs_component(Vec3(centre)))) || !std::isfinite(radius)) radius = 1.0;
  radius = std::min(radius, 1e9);
}

/// The sky: a box of half-size 4 radii around the model, its faces emitting inwards.
std::string add_sky(Scene& scene, const Box3& bounds, float scale) {
  glm::dvec3 centre;
  double radius = 0.0;
  rig_frame(bounds, centre, radius);
  const double half = 4.0 * radius;
  struct Face {
    glm::dvec3 outward;
    const char* name;
    double radiance;
  };
  // The default camera looks down -z from +z (frame_box): +z is behind it, -z is the background it sees.
  const Face faces[] = {{{0, 1, 0}, "lueur-sky-top", 1.1},     {{0, 0, 1}, "lueur-sky-key", 0.7},
                        {{1, 0, 0}, "lueur-sky-right", 0.2},   {{-1, 0, 0}, "lueur-sky-left", 0.2},
                        {{0, 0, -1}, "lueur-sky-ahead", 0.2}, {{0, -1, 0}, "lueur-sky-below", 0.05}};
  for (const Face& face : faces) {
    const uint32_t material = add_emitting_material(scene, face.name, face.radiance * scale);
    // Two tangents whose cross product points inwards: the quad then emits toward the model.
    glm::dvec3 t1 = std::abs(face.outward.y) > 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 t2 = glm::cross(face.outward, t1);
    if (glm::dot(glm::cross(t1, t2), face.outward) > 0.0) std::swap(t1, t2);
    auto corner = [&](double a, double b) { return Vec3(centre + half * (face.outward + a * t1 + b * t2)); };
    add_quad(scene, corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), material);
  }
  return "a sky box of 12 emitting triangles 8 model radii wide (brightest above, then behind the camera)";
}

/// The room's panel: above the inside point, nine tenths of the way to the ceiling (fixtures flush with the ceiling
/// then stay clear of it), facing down.
std::string add_ceiling_panel(Scene& scene, const Box3& bounds, const Enclosure& room, float scale) {
  const Vec3 extent = bounds.hi - bounds.lo;
  const double height = 0.9 * room.up + room.down;
  const glm::dvec3 centre(room.inside.x, room.inside.y + 0.9 * room.up, room.inside.z);
  // A quarter of the room's width and depth, but never wider than the room is high (a panel that fills the ceiling
  // would light the walls more than the floor).
  const double half_x = 0.5 * std::min<double>(0.25 * extent.x, height);
  const double half_z = 0.5 * std::min<double>(0.25 * extent.z, height);
  // Irradiance per unit radiance at the floor straight below: cos cos / d^2 summed over a 16 x 16 grid of the panel.
  double per_radiance = 0.0;
  constexpr int kCells = 16;
  const double cell_area = (2.0 * half_x / kCells) * (2.0 * half_z / kCells);
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const double x = -half_x + (i + 0.5) * 2.0 * half_x / kCells, z = -half_z + (j + 0.5) * 2.0 * half_z / kCells;
      const double d2 = x * x + z * z + height * height;
      per_radiance += height * height / (d2 * d2) * cell_area;  // cos_floor cos_panel / d^2 = h^2 / d^4
    }
  // E = pi makes the white floor below reflect 1: a single light must reach the room's far end too.
  const double radiance = per_radiance > 0.0 ? kPi / per_radiance : 1.0;
  const uint32_t material = add_emitting_material(scene, "lueur-room-light", radiance * scale);
  const float x0 = static_cast<float>(centre.x - half_x), x1 = static_cast<float>(centre.x + half_x);
  const float z0 = static_cast<float>(centre.z - half_z), z1 = static_cast<float>(centre.z + half_z);
  const float y = static_cast<float>(centre.y);
  add_quad(scene, Vec3(x0, y, z0), Vec3(x1, y, z0), Vec3(x1, y, z1), Vec3(x0, y, z1), material);  // normal -y
  char what[160];
  std::snprintf(what, sizeof what, "a %.3g x %.3g light panel under the closed room's ceiling", 2.0 * half_x,
                2.0 * half_z);
  return what;
}

}  // namespace

RayCast model_ray_cast(const Scene& scene) {
  // The model's triangles in runs of kRun, each run with a box around its corners, so that a ray tests only the
  // triangles of the runs whose box it crosses: a scene of millions of triangles without emitters is probed in
  // milliseconds rather than seconds. Runs in order and triangles in order within them, with a strict "nearer":
  // the nearest hit and its side are the ones a loop over every triangle finds.
  constexpr size_t kRun = 64;
  const size_t model = std::min<size_t>(scene.triangles.size(), scene.rig_begin);
  auto boxes = std::make_shared<std::vector<std::array<glm::dvec3, 2>>>((model + kRun - 1) / kRun);
  for (size_t run = 0; run < boxes->size(); ++run) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (size_t i = run * kRun; i < std::min(model, (run + 1) * kRun); ++i)
      for (const uint32_t v : scene.triangles[i].v) {
        lo = glm::min(lo, glm::dvec3(scene.positions[v]));
        hi = glm::max(hi, glm::dvec3(scene.positions[v]));
      }
    // Widened well beyond rounding, so that a hit on the box's very surface is never culled.
    const glm::dvec3 pad = 1e-6 * (glm::dvec3(1.0) + glm::max(glm::abs(lo), glm::abs(hi)));
    (*boxes)[run] = {lo - pad, hi + pad};
  }
  return [&scene, model, boxes](const Vec3& origin, const Vec3& dir, bool& front) {
    double best = std::numeric_limits<double>::infinity();
    const glm::dvec3 o(origin), d(dir);
    const auto crosses = [&](const std::array<glm::dvec3, 2>& box) {
      double near = 0.0, far = best;
      for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] == 0.0) {
          if (o[axis] < box[0][axis] || o[axis] > box[1][axis]) return false;
          continue;
        }
        double t0 = (box[0][axis] - o[axis]) / d[axis], t1 = (box[1][axis] - o[axis]) / d[axis];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
      }
      return near <= far;  // false for NaN too: such a box holds no triangle a ray can hit
    };
    for (size_t run = 0; run < boxes->size(); ++run) {
      if (!crosses((*boxes)[run])) continue;
      for (size_t i = run * kRun; i < std::min(model, (run + 1) * kRun); ++i) {
        const Triangle& tri = scene.triangles[i];
        double t = 0.0;
        bool f = false;
        if (hit_triangle(o, d, glm::dvec3(scene.positions[tri.v[0]]), glm::dvec3(scene.positions[tri.v[1]]),
                         glm::dvec3(scene.positions[tri.v[2]]), t, f) &&
            t < best) {
          best = t;
          front = f;
        }
      }
    }
    return static_cast<float>(best);
  };
}

std::optional<Enclosure> find_enclosure(const Box3& bounds, const RayCast& cast) {
  if (bounds.empty()) return std::nullopt;
  const Vec3 lo = bounds.lo, e = bounds.hi - bounds.lo;
  const Vec3 long_axis = e.x >= e.z ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
  const Vec3 short_axis = e.x >= e.z ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
  const float along = glm::dot(e, long_axis), across = glm::dot(e, short_axis);
  const Vec3 candidates[] = {lo + 0.3f * along * long_axis + 0.6f * e.y * Vec3(0, 1, 0) + 0.5f * across * short_axis,
                             bounds.center(), bounds.center() + 0.2f * e.y * Vec3(0, 1, 0)};
  for (const Vec3& point : candidates) {
    if (!is_finite(point) || !inside_room(point, cast)) continue;
    bool front = false;
    const float up = cast(point, Vec3(0, 1, 0), front), down = cast(point, Vec3(0, -1, 0), front);
    if (!std::isfinite(up) || !std::isfinite(down)) continue;
    Enclosure room;
    room.inside = point;
    room.up = up;
    room.down = down;
    room.long_axis = long_axis;
    return room;
  }
  return std::nullopt;
}

CameraSpec inside_view(const Box3& bounds, const Enclosure& room) {
  const Vec3 e = bounds.hi - bounds.lo;
  // Toward the farther end of the long axis, at 95% of the way, a third of the way up from the floor.
  const float at = glm::dot(room.inside - bounds.lo, room.long_axis);
  const float length = glm::dot(e, room.long_axis);
  const float far_end = at < 0.5f * length ? 0.95f * length : 0.05f * length;
  CameraSpec spec;
  spec.eye = room.inside;
  spec.target = room.inside + (far_end - at) * room.long_axis;
  spec.target.y = bounds.lo.y + 0.3f * e.y;
  spec.up = Vec3(0, 1, 0);
  spec.fovy_degrees = 60.0f;
  return spec;
}

std::string add_light_rig(Scene& scene, const std::optional<Enclosure>& room, float scale) {
  const Box3 bounds = scene.bounds();
  scene.rig_begin = static_cast<uint32_t>(scene.triangles.size());
  std::string what = room ? add_ceiling_panel(scene, bounds, *room, scale) : add_sky(scene, bounds, scale);
  collect_emitters(scene);
  return what;
}

}  // namespace lueur
