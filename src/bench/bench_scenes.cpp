// Loading and generating the benchmark scenes.
#include "bench/bench_scenes.h"

#include <filesystem>
#include <optional>
#include <random>

#include "scene/default_scene.h"
#include "scene/obj_loader.h"

namespace lueur::bench {
namespace {

constexpr int kSphereSegments = 64, kSphereRings = 32;
constexpr size_t kTrianglesPerSphere = 2 * kSphereSegments * (kSphereRings - 1);

void add_sphere(Scene& scene, const Vec3& centre, float radius, uint32_t material) {
  const auto base = static_cast<uint32_t>(scene.positions.size());
  // Rings of vertices from pole to pole; the poles are repeated per segment so every triangle has area.
  for (int r = 0; r <= kSphereRings; ++r) {
    const float theta = kPi * static_cast<float>(r) / kSphereRings;
    for (int s = 0; s < kSphereSegments; ++s) {
      const float phi = 2.0f * kPi * static_cast<float>(s) / kSphereSegments;
      scene.positions.push_back(
          centre + radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
    }
  }
  auto at = [&](int r, int s) { return base + static_cast<uint32_t>(r * kSphereSegments + s % kSphereSegments); };
  for (int r = 0; r < kSphereRings; ++r)
    for (int s = 0; s < kSphereSegments; ++s) {
      Triangle a, b;
      a.material = b.material = material;
      // Outward-facing (counter-clockwise seen from outside); the pole rows need only one triangle per quad.
      if (r != 0) {
        a.v[0] = at(r, s), a.v[1] = at(r, s + 1), a.v[2] = at(r + 1, s);
        scene.triangles.push_back(a);
      }
      if (r != kSphereRings - 1) {
        b.v[0] = at(r, s + 1), b.v[1] = at(r + 1, s + 1), b.v[2] = at(r + 1, s);
        scene.triangles.push_back(b);
      }
    }
}

/// Removes the triangles whose material emits (for a closed room: the default light the loader put above it).
void drop_emitters(Scene& scene) {
  std::erase_if(scene.triangles, [&](const Triangle& t) { return scene.materials[t.material].emissive(); });
  collect_emitters(scene);
}

/// A quad light inside the box, below its top, facing down: for closed rooms, whose default light sits above
/// the roof where every shadow ray would stop at the ceiling.
uint32_t add_interior_light(Scene& scene) {
  const Box3 box = scene.bounds();
  const Vec3 c = box.center(), e = box.extent();
  const float y = box.lo.y + 0.9f * e.y, hx = 0.1f * e.x, hz = 0.1f * e.z;
  Material light;
  light.name = "bench-light";
  light.kd = Vec3(0.0f);
  light.ke = Vec3(10.0f);
  const auto material = static_cast<uint32_t>(scene.materials.size());
  scene.materials.push_back(light);
  const auto first = static_cast<uint32_t>(scene.triangles.size());
  // Counter-clockwise seen from below: the light faces -y.
  add_quad(scene, Vec3(c.x - hx, y, c.z - hz), Vec3(c.x + hx, y, c.z - hz), Vec3(c.x + hx, y, c.z + hz),
           Vec3(c.x - hx, y, c.z + hz), material);
  collect_emitters(scene);
  return first;
}

BenchScene from_file(const std::string& name, const std::string& path, bool inside) {
  BenchScene b;
  b.name = name;
  b.scene = load_obj(path).scene;
  b.scene.name = name;
  b.path = path;
  if (inside) {
    // The benchmark's own small ceiling light replaces whatever the loader added (today the rig's panel under the
    // ceiling; when this scene was first measured, a light above the roof), so that its figures compare across
    // sessions. The store section can race the room under the rig's panel instead (--store-conference-light rig).
    drop_emitters(b.scene);
    const Box3 box = b.scene.bounds();
    // From a third of the way along the room (the conference room's end is walled off behind a pillar), at 60% of
    // its height, toward the lower part of the far end: down the table, as the room is usually shown.
    const Vec3 lo = box.lo, e = box.extent();
    const uint32_t light = add_interior_light(b.scene);
    b.lights = {light, light + 1};
    b.view.eye = lo + Vec3(0.3f, 0.6f, 0.5f) * e;
    b.view.target = lo + Vec3(0.95f, 0.3f, 0.5f) * e;
    b.view.fovy_degrees = 60.0f;
  } else {
    b.lights = b.scene.emitters;
    b.view = frame_box(b.scene.bounds());
  }
  return b;
}

}  // namespace

BenchScene make_room_facing_wall() {
  BenchScene room;
  room.name = "room";
  Scene& scene = room.scene;
  scene.name = room.name;
  const auto material = [&](const char* name, Vec3 kd, Vec3 ke) {
    Material m;
    m.name = name;
    m.kd = kd;
    m.ke = ke;
    scene.materials.push_back(m);
    return static_cast<uint32_t>(scene.materials.size() - 1);
  };
  const uint32_t white = material("white", Vec3(0.7f), Vec3(0.0f)),
                 red = material("red", Vec3(0.7f, 0.15f, 0.1f), Vec3(0.0f)),
                 green = material("green", Vec3(0.15f, 0.6f, 0.15f), Vec3(0.0f)),
                 light = material("panel", Vec3(0.0f), Vec3(12.0f));
  // Every face counter-clockwise as seen from inside, so that its normal points into the room.
  const float x0 = -2.0f, x1 = 2.0f, y0 = 0.0f, y1 = 3.0f, z0 = -3.0f, z1 = 3.0f;
  add_quad(scene, {x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}, white);  // floor
  add_quad(scene, {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, white);  // ceiling
  add_quad(scene, {x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, red);    // left wall
  add_quad(scene, {x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}, green);  // right wall
  add_quad(scene, {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, white);  // back wall, behind the camera
  add_quad(scene, {x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}, white);  // the wall the camera faces
  // A block on the floor behind the camera: shadows where only bounce rays go. Its faces point outwards.
  const Vec3 lo(-1.5f, 0.0f, -1.5f), hi(-0.3f, 1.2f, -0.4f);
  add_quad(scene, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, white);  // top
  add_quad(scene, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}, white);  // -x
  add_quad(scene, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}, white);  // +x
  add_quad(scene, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z}, white);  // -z
  add_quad(scene, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, white);  // +z
  // The panel, just under the ceiling behind the camera, facing down.
  const float y = y1 - 0.01f;
  add_quad(scene, {-0.5f, y, -2.6f}, {0.5f, y, -2.6f}, {0.5f, y, -1.8f}, {-0.5f, y, -1.8f}, light);
  collect_emitters(scene);
  room.lights = scene.emitters;
  room.view.eye = Vec3(0.0f, 1.5f, 1.2f);
  room.view.target = Vec3(0.0f, 1.4f, 3.0f);
  room.view.fovy_degrees = 40.0f;
  return room;
}

int spheres_for(size_t triangles) { return std::max(1, static_cast<int>(triangles / kTrianglesPerSphere)); }

BenchScene make_sphere_field(int spheres, uint32_t seed) {
  BenchScene field;
  Scene& scene = field.scene;
  scene.name = "spheres";
  Material grey;
  grey.kd = Vec3(0.6f);
  scene.materials.push_back(grey);
  // Spheres in a square whose side grows with their number, so density (and overlap) stays the same.
  const float side = 10.0f * std::sqrt(static_cast<float>(spheres));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < spheres; ++i) {
    const float radius = 1.0f + 3.0f * u01(rng) * u01(rng);
    const Vec3 centre(side * u01(rng), radius + 6.0f * u01(rng), side * u01(rng));
    add_sphere(scene, centre, radius, 0);
  }
  add_quad(scene, Vec3(-5.0f, 0.0f, -5.0f), Vec3(-5.0f, 0.0f, side + 5.0f), Vec3(side + 5.0f, 0.0f, side + 5.0f),
           Vec3(side + 5.0f, 0.0f, -5.0f), 0);
  // From above one corner, looking across the field.
  field.view.eye = Vec3(-0.1f * side, 0.25f * side, -0.1f * side);
  field.view.target = Vec3(0.5f * side, 0.0f, 0.5f * side);
  field.view.fovy_degrees = 50.0f;
  add_default_light(scene);
  field.lights = scene.emitters;
  field.name = "spheres-" + std::to_string(scene.triangles.size() / 1000) + "k";
  scene.name = field.name;
  return field;
}

namespace {

struct SharedScene {
  const char* name;
  const char* path;
  bool inside;  ///< a closed room: the camera and a light go inside
  bool in_quick;
  bool listed;  ///< in load_bench_scenes' list (otherwise only by its name)
};
constexpr SharedScene kSharedScenes[] = {
    {"cornell-water", "cornell-water/CornellBox-Water.obj", false, false, true},
    {"stanford-bunny", "stanford-bunny/stanford-bunny.obj", false, true, true},
    {"conference", "conference/conference.obj", true, false, true},
    {"cornell-original", "cornell-original/CornellBox-Original.obj", false, false, false}};

/// The shared scene, or nothing (its reason appended to `skipped`) where the folder or the file is missing.
std::optional<BenchScene> load_shared(const SharedScene& s, const std::string& shared_dir,
                                      std::vector<std::string>& skipped) {
  const std::filesystem::path path = std::filesystem::path(shared_dir) / s.path;
  std::error_code ec;
  if (shared_dir.empty() || !std::filesystem::exists(path, ec)) {
    skipped.push_back(std::string(s.name) +
                      (shared_dir.empty() ? " (no shared scenes folder)" : " (" + path.string() + " not found)"));
    return std::nullopt;
  }
  return from_file(s.name, path.string(), s.inside);
}

}  // namespace

BenchScene make_default_bench_scene() {
  BenchScene b;
  b.name = "default";
  b.scene = make_default_scene();
  compute_smooth_normals(b.scene);
  b.view = default_scene_camera();
  b.lights = b.scene.emitters;
  return b;
}

std::optional<BenchScene> load_shared_bench_scene(const std::string& name, const std::string& shared_dir,
                                                  std::vector<std::string>& skipped) {
  for (const SharedScene& s : kSharedScenes)
    if (name == s.name) return load_shared(s, shared_dir, skipped);
  return std::nullopt;
}

std::vector<BenchScene> load_bench_scenes(bool quick, const std::string& shared_dir,
                                          std::vector<std::string>& skipped) {
  std::vector<BenchScene> scenes;
  scenes.push_back(make_default_bench_scene());
  for (const SharedScene& s : kSharedScenes) {
    if (!s.listed || (quick && !s.in_quick)) continue;
    if (std::optional<BenchScene> b = load_shared(s, shared_dir, skipped)) scenes.push_back(std::move(*b));
  }
  scenes.push_back(make_sphere_field(spheres_for(quick ? 100000 : 2000000), 7));
  return scenes;
}

}  // namespace lueur::bench
