// The default light rig and closed rooms: a scene without emitters gets a sky (outside) or a ceiling panel (in a
// closed room) of emissive triangles that every light strategy samples, with the light it was designed to give;
// closed rooms are told from open scenes and from closed solids, and get a view from inside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "integrator/camera_light.h"
#include "integrator/direct_light.h"
#include "integrator/renderer.h"
#include "obj_test_support.h"
#include "scene/light_rig.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

/// Irradiance at p (normal n) from every emitter of `scene`, by the midpoint rule on a cells x cells split of each
/// triangle's parallelogram (half of whose cells lie outside it and are skipped), the receiver's cosine clamped at
/// 0: light from below p's horizon counts for nothing. Independent of the rig's own arithmetic.
double irradiance_by_quadrature(const Scene& scene, const Vec3& p, const Vec3& n, int cells = 200) {
  double e = 0.0;
  for (const uint32_t t : scene.emitters) {
    const Triangle& tri = scene.triangles[t];
    const glm::dvec3 a(scene.positions[tri.v[0]]), b(scene.positions[tri.v[1]]), c(scene.positions[tri.v[2]]);
    const glm::dvec3 e1 = b - a, e2 = c - a, cross = glm::cross(e1, e2);
    const glm::dvec3 light_normal = glm::normalize(cross);
    // The triangle cut into cells^2 similar triangles (cells (cells + 1) / 2 upright, the rest upside down), each
    // taken at its centroid: the cells cover the triangle exactly.
    const double cell_area = 0.5 * glm::length(cross) / (static_cast<double>(cells) * cells);
    const auto add = [&](double u, double v) {
      const glm::dvec3 d = a + u * e1 + v * e2 - glm::dvec3(p);
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      const double cos_receiver = std::max(0.0, glm::dot(glm::dvec3(n), d) / r);
      const double cos_light = std::max(0.0, -glm::dot(light_normal, d) / r);
      e += scene.material_of(t).ke.r * cos_receiver * cos_light / r2 * cell_area;
    };
    for (int i = 0; i < cells; ++i)
      for (int j = 0; i + j < cells; ++j) {
        add((i + 1.0 / 3.0) / cells, (j + 1.0 / 3.0) / cells);
        if (i + j + 2 <= cells) add((i + 2.0 / 3.0) / cells, (j + 2.0 / 3.0) / cells);
      }
  }
  return e;
}

/// The corners of a box, OBJ-numbered from `first`: the bottom face, then the top face, each counter-clockwise
/// seen from above.
std::string box_vertices(Vec3 lo, Vec3 hi) {
  std::string text;
  for (const float y : {lo.y, hi.y})
    for (const auto& [x, z] : {std::pair{lo.x, lo.z}, {hi.x, lo.z}, {hi.x, hi.z}, {lo.x, hi.z}}) {
      char line[96];
      std::snprintf(line, sizeof line, "v %g %g %g\n", static_cast<double>(x), static_cast<double>(y),
                    static_cast<double>(z));
      text += line;
    }
  return text;
}

/// The six faces of the box whose corners start at OBJ index `first`, facing out of it (or, reversed, into it).
std::string box_faces(int first, bool inwards) {
  const int faces[6][4] = {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2}, {4, 3, 7, 8}, {1, 4, 8, 5}, {2, 6, 7, 3}};
  std::string text;
  for (const auto& face : faces) {
    char line[64];
    const auto corner = [&](int k) { return first - 1 + face[inwards ? 3 - k : k]; };
    std::snprintf(line, sizeof line, "f %d %d %d %d\n", corner(0), corner(1), corner(2), corner(3));
    text += line;
  }
  return text;
}

/// A closed room 8 x 3 x 5 whose six walls face inwards, with a table (a closed box facing outwards) in it.
std::string closed_room_obj() {
  return box_vertices({0, 0, 0}, {8, 3, 5}) + box_faces(1, true) + box_vertices({5, 0, 2}, {6, 0.8f, 3}) +
         box_faces(9, false);
}

/// The same box's six faces turned outwards: a closed solid, not a room.
std::string closed_solid_obj() { return box_vertices({0, 0, 0}, {8, 3, 5}) + box_faces(1, false); }

TEST(LightRig, OpenSceneGetsASkyThatLightsTheModelAsDesigned) {
  // A unit quad facing up at the origin: no emitter, not a room.
  const LoadedScene loaded = load_obj_from_text("v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nf 1 2 3 4\n", "", "quad.obj");
  const Scene& scene = loaded.scene;
  EXPECT_TRUE(test::has_warning(loaded, "no emitter: added the default light rig, a sky box"))
      << test::all_warnings(loaded);
  ASSERT_EQ(scene.rig_begin, 2u);
  ASSERT_EQ(scene.triangles.size(), 14u);
  EXPECT_EQ(scene.emitters.size(), 12u);
  // The model's bounds leave the rig out: the camera frames the quad, not the sky.
  EXPECT_EQ(scene.bounds().lo, Vec3(-1, 0, -1));
  EXPECT_EQ(scene.bounds().hi, Vec3(1, 0, 1));
  // Every sky triangle faces the model.
  for (uint32_t t = scene.rig_begin; t < scene.triangles.size(); ++t)
    EXPECT_LT(glm::dot(scene.geometric_normal_raw(t), scene.point(t, 1.0f / 3, 1.0f / 3)), 0.0f) << t;
  // A white surface facing up at the sky's centre (light_rig.h): the top face fills the form factor of a square
  // seen from a depth of its half-side (four corner rectangles of 1 x 1 depths), the sides' upper halves the rest of
  // the hemisphere, each a quarter of it. Facing the camera (+z), less.
  const auto corner_rectangle = [](double x, double y) {  // form factor to an x by y rectangle above a corner
    const double sx = std::sqrt(1.0 + x * x), sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
  };
  const double top = 4.0 * corner_rectangle(1.0, 1.0);
  const double expected_up = 1.1 * top + (0.7 + 3 * 0.2) * (1.0 - top) / 4.0;
  const double up = irradiance_by_quadrature(scene, Vec3(0.0f), Vec3(0, 1, 0)) / kPi;
  EXPECT_NEAR(up, expected_up, 1e-4 * expected_up);
  const double toward_camera = irradiance_by_quadrature(scene, Vec3(0.0f), Vec3(0, 0, 1)) / kPi;
  EXPECT_GT(toward_camera, 0.3);
  EXPECT_LT(toward_camera, up);
  const double away = irradiance_by_quadrature(scene, Vec3(0.0f), Vec3(0, 0, -1)) / kPi;
  EXPECT_LT(away, toward_camera);  // the key is behind the camera
}

TEST(LightRig, ScaleAndOff) {
  const std::string quad = "v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nf 1 2 3 4\n";
  LoadOptions options;
  options.light_rig_scale = 2.0f;
  const LoadedScene twice = load_obj_from_text(quad, "", "quad.obj", options);
  const LoadedScene once = load_obj_from_text(quad, "", "quad.obj");
  for (size_t k = 0; k < once.scene.emitters.size(); ++k)
    EXPECT_FLOAT_EQ(twice.scene.material_of(twice.scene.emitters[k]).ke.r,
                    2.0f * once.scene.material_of(once.scene.emitters[k]).ke.r);
  options.light_rig = false;
  const LoadedScene off = load_obj_from_text(quad, "", "quad.obj", options);
  EXPECT_TRUE(off.scene.emitters.empty());
  EXPECT_EQ(off.scene.triangles.size(), 2u);
  EXPECT_TRUE(test::has_warning(off, "the default light rig is off: nothing lights the scene"));
  // A file's own emitters mean no rig at all.
  const LoadedScene lit = load_obj_from_text(quad + "mtllib l.mtl\nusemtl lamp\nv 0 2 0\nv 1 2 0\nv 0 2 1\nf 6 7 5\n",
                                             "newmtl lamp\nKe 1 1 1\n", "lit.obj");
  EXPECT_EQ(lit.scene.rig_begin, Scene::kNoRig);
  EXPECT_EQ(lit.scene.emitters.size(), 1u);
}

TEST(LightRig, ClosedRoomIsLitFromInsideAsDesigned) {
  const LoadedScene loaded = load_obj_from_text(closed_room_obj(), "", "room.obj");
  const Scene& scene = loaded.scene;
  EXPECT_TRUE(test::has_warning(loaded, "light panel under the closed room's ceiling")) << test::all_warnings(loaded);
  ASSERT_EQ(scene.emitters.size(), 2u);
  // The panel hangs just under the ceiling, facing down, inside the room.
  for (const uint32_t t : scene.emitters) {
    EXPECT_LT(scene.geometric_normal_raw(t).y, 0.0f);
    for (const uint32_t v : scene.triangles[t].v) {
      EXPECT_GT(scene.positions[v].y, 2.5f);
      EXPECT_LT(scene.positions[v].y, 3.0f);
      EXPECT_GT(scene.positions[v].x, 0.0f);
      EXPECT_LT(scene.positions[v].x, 8.0f);
    }
  }
  // The floor straight below the panel's centre reads 1 for a white surface (Lambert's formula, independent of
  // the rig's own quadrature), and L1 there is rho/pi E with every light strategy.
  const Triangle& panel = scene.triangles[scene.emitters[0]];
  const Vec3 below(0.5f * (scene.positions[panel.v[0]].x + scene.positions[panel.v[2]].x), 0.0f,
                   0.5f * (scene.positions[panel.v[0]].z + scene.positions[panel.v[2]].z));
  double e = 0.0;
  for (const uint32_t t : scene.emitters) {
    const Triangle& tri = scene.triangles[t];
    e += test::lambert_irradiance({glm::dvec3(scene.positions[tri.v[0]]), glm::dvec3(scene.positions[tri.v[1]]),
                                   glm::dvec3(scene.positions[tri.v[2]])},
                                  glm::dvec3(below), glm::dvec3(0, 1, 0), scene.material_of(t).ke.r);
  }
  EXPECT_NEAR(e / kPi, 1.0, 0.01);
  const auto traced = prepare_scene(scene);
  const std::optional<SurfacePoint> sp = test::surface_below(*traced, below, 1.0f);
  ASSERT_TRUE(sp);
  for (const LightStrategy strategy :
       {LightStrategy::kAll, LightStrategy::kUniform, LightStrategy::kArea, LightStrategy::kPower,
        LightStrategy::kImportance}) {
    DirectLightOptions options;
    options.strategy = strategy;
    options.rays = 4096;
    options.blinn_k = 1.0f;
    PixelSampler sampler(SamplerKind::kSobol, 3, 0, 0, RngPurpose::kDirect);
    uint64_t rays = 0;
    const Vec3 l1 = estimate_direct_light(*traced, *sp, options, sampler, 0, rays);
    EXPECT_NEAR(l1.r, 0.5 * e / kPi, 0.01 * 0.5 * e / kPi) << kLightStrategyNames[static_cast<size_t>(strategy)];
  }
}

/// Two triangles over the four positions from `base` on.
void add_quad_indices(Scene& scene, uint32_t base) {
  Triangle a, b;
  a.v[0] = base, a.v[1] = base + 1, a.v[2] = base + 2;
  b.v[0] = base, b.v[1] = base + 2, b.v[2] = base + 3;
  scene.triangles.push_back(a);
  scene.triangles.push_back(b);
}

/// The nearest hit over every triangle of the model (the rig excluded), in double: the oracle of the culled cast.
float nearest_by_loop(const Scene& scene, const Vec3& origin, const Vec3& dir, bool& front) {
  double best = std::numeric_limits<double>::infinity();
  const glm::dvec3 o(origin), d(dir);
  for (size_t i = 0; i < std::min<size_t>(scene.triangles.size(), scene.rig_begin); ++i) {
    const Triangle& tri = scene.triangles[i];
    const glm::dvec3 a(scene.positions[tri.v[0]]), e1 = glm::dvec3(scene.positions[tri.v[1]]) - a,
                                                   e2 = glm::dvec3(scene.positions[tri.v[2]]) - a;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (!(std::abs(det) > 1e-300)) continue;
    const double inv = 1.0 / det;
    const glm::dvec3 sv = o - a;
    const double u = glm::dot(sv, p) * inv;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 q = glm::cross(sv, e1);
    const double v = glm::dot(d, q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, q) * inv;
    if (t > 0.0 && t < best) {
      best = t;
      front = glm::dot(glm::cross(e1, e2), d) < 0.0;
    }
  }
  return static_cast<float>(best);
}

TEST(LightRig, TheModelRayCastFindsWhatALoopOverEveryTriangleFinds) {
  // A closed box of axis-aligned quads (rays along its faces and from its corners graze the runs' boxes) and
  // thousands of scattered triangles, probed by random rays and by axis-aligned ones.
  Scene scene = load_obj_from_text(closed_room_obj(), "", "room.obj").scene;
  scene.triangles.resize(std::min<size_t>(scene.triangles.size(), scene.rig_begin));
  // And flat runs: a floor of 8 x 16 quads at y = 3, whose boxes have no thickness at all.
  for (int z = 0; z < 16; ++z)
    for (int x = 0; x < 8; ++x) {
      const auto base = static_cast<uint32_t>(scene.positions.size());
      for (const auto& [dx, dz] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}})
        scene.positions.emplace_back(static_cast<float>(x + dx), 3.0f, static_cast<float>(z + dz));
      add_quad_indices(scene, base);
    }
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-2.0f, 12.0f), unit(-1.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    Triangle tri;
    const Vec3 at(coordinate(rng), coordinate(rng), coordinate(rng));
    for (uint32_t& v : tri.v) {
      v = static_cast<uint32_t>(scene.positions.size());
      scene.positions.push_back(at + 0.3f * Vec3(unit(rng), unit(rng), unit(rng)));
    }
    scene.triangles.push_back(tri);
  }
  scene.rig_begin = static_cast<uint32_t>(scene.triangles.size());
  const RayCast cast = model_ray_cast(scene);
  const Box3 box = scene.bounds();
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    Vec3 origin(coordinate(rng), coordinate(rng), coordinate(rng)), dir(unit(rng), unit(rng), unit(rng));
    if (i % 3 == 1) dir = Vec3(0.0f), dir[i % 9 / 3] = unit(rng) < 0 ? -1.0f : 1.0f;            // along an axis
    if (i % 5 == 2) origin = scene.positions[static_cast<size_t>(i) % scene.positions.size()];  // on a corner
    if (i % 7 == 3) origin.x = box.lo.x;                                                        // on the box's side
    if (i % 11 == 4) origin = Vec3(coordinate(rng) * 0.6f, 3.0f, coordinate(rng));              // in the floor's plane
    if (i % 13 == 5)
      origin = Vec3(0.5f + static_cast<float>(i % 8), 6.0f, 0.5f + static_cast<float>(i % 16)),
      dir = Vec3(0.0f, -1.0f, 0.0f);  // straight down onto the floor
    if (glm::length(dir) == 0.0f) continue;
    dir = glm::normalize(dir);
    bool front = false, expected_front = false;
    const float t = cast(origin, dir, front), expected = nearest_by_loop(scene, origin, dir, expected_front);
    ASSERT_EQ(t, expected) << "ray " << i;
    if (std::isfinite(expected)) {
      EXPECT_EQ(front, expected_front) << "ray " << i;
      ++hits;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(LightRig, RoomsAreToldFromOpenScenesAndClosedSolids) {
  const LoadedScene room = load_obj_from_text(closed_room_obj(), "", "room.obj");
  const LoadedScene solid = load_obj_from_text(closed_solid_obj(), "", "solid.obj");
  // The room without its ceiling: open.
  std::string open_text = closed_room_obj();
  open_text.replace(open_text.find("f 6 7 8 5\n"), 10, "");  // the ceiling, facing down
  const LoadedScene open = load_obj_from_text(open_text, "", "open.obj");
  const auto probe = [](const Scene& s) {
    Scene model = s;
    model.rig_begin = std::min<uint32_t>(s.rig_begin, static_cast<uint32_t>(s.triangles.size()));
    return find_enclosure(model.bounds(), model_ray_cast(model));
  };
  const std::optional<Enclosure> inside = probe(room.scene);
  ASSERT_TRUE(inside);
  EXPECT_FALSE(probe(solid.scene)) << "from inside a closed solid the rays meet back faces";
  EXPECT_FALSE(probe(open.scene));
  // The view from inside stands in the room and looks along its 8-long axis, toward its far end.
  const CameraSpec view = inside_view(room.scene.bounds(), *inside);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_GT(view.eye[axis], room.scene.bounds().lo[axis]);
    EXPECT_LT(view.eye[axis], room.scene.bounds().hi[axis]);
  }
  EXPECT_GT(std::abs(view.target.x - view.eye.x), 3.0f);
  EXPECT_NEAR(view.target.z, view.eye.z, 1e-4f);
  EXPECT_EQ(solid.scene.emitters.size(), 12u) << "a closed solid gets the sky";
}

TEST(LightRig, HeadlessOpensAClosedRoomFromInsideAndSaysSo) {
  const std::string dir = test::make_temp_dir("light-rig-room");
  const std::string path = test::write_text(dir, "room.obj", closed_room_obj());
  const std::string image = dir + "/room.pfm";
  // A small headless render of `scene`, with `options` added; it must succeed, and its output is returned.
  const auto render = [&](const std::string& scene, const std::string& options) {
    const test::CommandResult r = test::run_lueur(test::shell_quote(scene) + " --headless --size 32x24 --frames 2 " +
                                                  "--passes l1 " + options + " --out " + test::shell_quote(image));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return r.output;
  };
  const std::string inside = render(path, "");
  EXPECT_NE(inside.find("is a closed room: the camera starts inside it"), std::string::npos) << inside;
  const std::string outside = render(path, "--camera outside");
  EXPECT_NE(outside.find("from outside the camera sees its walls (--camera inside"), std::string::npos) << outside;
  const std::string not_a_room = render(test::write_text(dir, "solid.obj", closed_solid_obj()), "--camera inside");
  EXPECT_NE(not_a_room.find("is not a closed room: no view from inside"), std::string::npos) << not_a_room;
}

TEST(CameraLight, LightsWhatTheCameraSeesAsDesigned) {
  // A 10 x 10 white-ish wall facing +z, no emitter and no rig; the camera at half the diagonal looks at its centre.
  LoadOptions no_rig;
  no_rig.light_rig = false;
  const auto traced = prepare_scene(
      load_obj_from_text("v -5 -5 0\nv 5 -5 0\nv 5 5 0\nv -5 5 0\nf 1 2 3 4\n", "", "wall.obj", no_rig).scene);
  ASSERT_TRUE(traced->lights.empty());
  const float distance = 0.5f * traced->diagonal;
  const Camera camera = make_camera({Vec3(0, 0, distance), Vec3(0.0f), Vec3(0, 1, 0), 40.0f}, 16, 16);
  const EmitterRecord head = make_camera_light(camera, traced->diagonal);
  EXPECT_NEAR(glm::dot(head.normal, camera.forward), 1.0f, 1e-6f);  // it shines where the camera looks
  EXPECT_LT(glm::dot(head.p0 - camera.eye, camera.forward), 0.0f);  // from behind the eye

  const Ray ray = camera_ray(camera, 8.0f, 8.0f);
  const Hit hit = intersect_closest(traced->accel, ray);
  ASSERT_TRUE(hit.found());
  const SurfacePoint sp = make_surface_point(traced->scene, ray, hit);
  DirectLightOptions options;
  options.rays = 1024;
  options.blinn_k = 1.0f;
  uint64_t rays = 0;
  PixelSampler off_sampler(SamplerKind::kSobol, 5, 0, 0, RngPurpose::kDirect);
  EXPECT_EQ(estimate_direct_light(*traced, sp, options, off_sampler, 0, rays), Vec3(0.0f));
  options.camera_light = &head;
  PixelSampler sampler(SamplerKind::kSobol, 5, 0, 0, RngPurpose::kDirect);
  const Vec3 l1 = estimate_direct_light(*traced, sp, options, sampler, 0, rays);
  const double e = test::lambert_irradiance({glm::dvec3(head.p0), glm::dvec3(head.p1), glm::dvec3(head.p2)},
                                            glm::dvec3(sp.position), glm::dvec3(0, 0, 1), head.ke.r);
  const double rho = traced->scene.material_of(hit.triangle).kd.r;
  EXPECT_NEAR(l1.r, rho / kPi * e, 0.005 * rho / kPi * e);
  EXPECT_NEAR(e / kPi, 1.0, 0.01);  // the design: a white surface there reads 1

  // Rendered: lit with the head-light, black without, and the same bytes on 1 and 2 threads.
  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.enabled = {false, true, true, false};
  settings.camera_light = true;
  const auto render = [&](int threads, bool head_light) {
    RenderSettings s = settings;
    s.camera_light = head_light;
    Film film;
    film.reset(s);
    ThreadPool pool(threads);
    for (int f = 0; f < 3; ++f) render_frame(*traced, camera, s, film, nullptr, pool);
    return pass_average(film, Pass::kL1).rgb;
  };
  const std::vector<float> one = render(1, true), two = render(2, true), dark = render(2, false);
  EXPECT_EQ(one, two);
  EXPECT_GT(*std::max_element(one.begin(), one.end()), 0.1f);
  EXPECT_EQ(*std::max_element(dark.begin(), dark.end()), 0.0f);
}

}  // namespace
}  // namespace lueur
