// Textures: the colour map (map_Kd) sampled where the renderer says, in every pass that reads an albedo, and the
// cutout mask (map_d) making holes for every ray in both back-ends; the loader reading them from MTL files and
// surviving missing and hostile images.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "integrator/direct_light.h"
#include "integrator/indirect_light.h"
#include "integrator/renderer.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

/// sRGB byte to linear, written out independently of the texture code.
float linear_of(int byte) {
  const double c = byte / 255.0;
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

/// A w x h texture whose texel (x, y), rows from the top, is `rgba(x, y)`.
template <typename Texel>
Texture make_texture(int w, int h, Texel rgba) {
  Texture t;
  t.width = w;
  t.height = h;
  t.has_alpha = true;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      for (const uint8_t channel : rgba(x, y)) t.rgba.push_back(channel);
    }
  return t;
}

constexpr int kDark = 51, kLight = 204;

/// An 8 x 8 checkerboard of 2 x 2-texel squares, dark in the top-left one: bilinear filtering leaves each square's
/// central half texel untouched.
Texture make_checkerboard() {
  return make_texture(8, 8, [](int x, int y) {
    const uint8_t v = ((x / 2 + y / 2) % 2 == 0) ? kDark : kLight;
    return std::array<uint8_t, 4>{v, v, v, 255};
  });
}

/// Appends the quad a b c d (texture coordinates (0,0) (1,0) (1,1) (0,1)) with `material`.
void add_textured_quad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material) {
  const auto first_triangle = s.triangles.size();
  const auto t0 = static_cast<uint32_t>(s.texcoords.size());
  s.texcoords.insert(s.texcoords.end(), {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
  add_quad(s, a, b, c, d, material);
  Triangle& first = s.triangles[first_triangle];
  Triangle& second = s.triangles[first_triangle + 1];
  first.t[0] = t0, first.t[1] = t0 + 1, first.t[2] = t0 + 2;
  second.t[0] = t0, second.t[1] = t0 + 2, second.t[2] = t0 + 3;
}

TEST(Texture, BilinearRepeatAndSrgbDecoding) {
  const Texture board = make_checkerboard();
  // The centre of the top-left square (texel corner (1, 1) from the top) and of its right neighbour.
  EXPECT_FLOAT_EQ(sample_albedo(board, Vec2(1.0f / 8, 7.0f / 8)).r, linear_of(kDark));
  EXPECT_FLOAT_EQ(sample_albedo(board, Vec2(3.0f / 8, 7.0f / 8)).g, linear_of(kLight));
  // Repeat: whole periods away (negative ones too) read the same.
  EXPECT_FLOAT_EQ(sample_albedo(board, Vec2(1.0f / 8 + 3.0f, 7.0f / 8 - 2.0f)).b, linear_of(kDark));
  // Halfway between the two texel centres across a square's edge: the mean of the two (linear values, blended).
  EXPECT_NEAR(sample_albedo(board, Vec2(2.0f / 8, 7.0f / 8 + 0.5f / 8)).r,
              0.5f * (linear_of(kDark) + linear_of(kLight)), 1e-6f);
  // Wrapping across the image's border blends the last column with the first.
  const Texture stripes = make_texture(2, 1, [](int x, int) {
    const uint8_t v = x == 0 ? 0 : 255;
    return std::array<uint8_t, 4>{v, v, v, static_cast<uint8_t>(v)};
  });
  EXPECT_NEAR(sample_albedo(stripes, Vec2(0.0f, 0.5f)).r, 0.5f, 1e-6f);
  EXPECT_NEAR(sample_coverage(stripes, Vec2(0.25f, 0.5f)), 0.0f, 1e-6f);
  EXPECT_NEAR(sample_coverage(stripes, Vec2(0.75f, 0.5f)), 1.0f, 1e-6f);
  // Hostile coordinates read as 0, never as an index.
  EXPECT_TRUE(std::isfinite(sample_albedo(board, Vec2(NAN, INFINITY)).r));
  EXPECT_TRUE(std::isfinite(sample_albedo(board, Vec2(-3e38f, 3e38f)).r));
}

/// A checkerboarded quad filling a 64 x 64 view, nothing else: every AO ray escapes, so AO is the albedo itself.
TEST(Texture, CheckerboardIsRenderedAtItsTexels) {
  Scene s;
  s.name = "checker";
  Material m;
  m.kd = Vec3(1.0f, 0.0f, 0.0f);  // replaced by the colour map
  m.diffuse_texture = 0;
  s.materials = {m};
  s.textures = {make_checkerboard()};
  add_textured_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, 0);
  const auto traced = prepare_scene(std::move(s));

  RenderSettings settings;
  settings.width = settings.height = 64;
  settings.enabled = {false, false, false, true};
  settings.ao_rays = 4;
  const CameraSpec spec{Vec3(0, 0, 2), Vec3(0, 0, 0), Vec3(0, 1, 0), 2.0f * glm::degrees(std::atan(0.5f))};
  const Camera camera = make_camera(spec, 64, 64);
  Film film;
  film.reset(settings);
  ThreadPool pool(2);
  for (int f = 0; f < 4; ++f) render_frame(*traced, camera, settings, film, nullptr, pool);
  const Image ao = pass_average(film, Pass::kAo);
  int checked = 0;
  for (int sy = 0; sy < 4; ++sy)
    for (int sx = 0; sx < 4; ++sx) {
      // The square's centre on the quad (texture v runs up, image rows down) and where the camera sees it.
      const Vec3 centre(-1.0f + 0.5f * (sx + 0.5f), 1.0f - 0.5f * (sy + 0.5f), 0.0f);
      float px = 0.0f, py = 0.0f;
      ASSERT_TRUE(project_to_pixel(camera, centre, px, py));
      const Vec3 seen = ao.at(static_cast<int>(px), static_cast<int>(py));
      const float expected = linear_of((sx + sy) % 2 == 0 ? kDark : kLight);
      EXPECT_FLOAT_EQ(seen.r, expected) << "square " << sx << "," << sy;
      EXPECT_FLOAT_EQ(seen.g, expected) << "square " << sx << "," << sy;
      ++checked;
    }
  EXPECT_EQ(checked, 16);
}

/// The closed emitting sphere of the analytic tests (bounded variance, unlike a box's edges), its Kd a wrong colour
/// and its one-texel colour map the right albedo: L1 = rho Le and L2 = rho^2 Le hold only if both p's and q's albedo
/// come from the map, with every kind of L1 reuse (the screen's L1 is rescaled to q's texel, the store's multiplied
/// by it).
TEST(Texture, ClosedSphereClosedFormsReadTheColourMap) {
  Scene s = test::make_closed_emitting_sphere(1.0f, 32, 16, Vec3(0.9f, 0.1f, 0.9f), Vec3(1.0f));
  const std::array<uint8_t, 4> texel = {128, 160, 96, 255};
  s.textures = {make_texture(1, 1, [&](int, int) { return texel; })};
  for (Material& m : s.materials) m.diffuse_texture = 0;
  const Vec3 rho(linear_of(texel[0]), linear_of(texel[1]), linear_of(texel[2]));
  const auto traced = prepare_scene(std::move(s));
  const CameraSpec spec{Vec3(0.1f, 0.2f, 0.0f), Vec3(-1, -0.5f, -0.3f), Vec3(0, 1, 0), 90.0f};
  for (const ReuseMode reuse : {ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kCache, ReuseMode::kScreenCache}) {
    RenderSettings settings;
    settings.width = settings.height = 12;
    settings.enabled = {false, true, true, false};
    settings.blinn_k = 1.0f;
    settings.l1_rays = settings.l2_rays = 8;
    settings.reuse = reuse;
    const Camera camera = make_camera(spec, 12, 12);
    Accumulation accumulation;
    accumulation.reset(settings);
    const Film& film = accumulation.film;
    ThreadPool pool(2);
    for (int f = 0; f < 64; ++f) render_frame(*traced, camera, settings, accumulation, pool);
    const Image l1 = pass_average(film, Pass::kL1), l2 = pass_average(film, Pass::kL2);
    Vec3 mean_l1(0.0f), mean_l2(0.0f);
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x) mean_l1 += l1.at(x, y) / 144.0f, mean_l2 += l2.at(x, y) / 144.0f;
    const std::string name(kReuseModeNames[static_cast<size_t>(reuse)]);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mean_l1[c], rho[c], 0.01f * rho[c]) << name << " channel " << c;
      EXPECT_NEAR(mean_l2[c], rho[c] * rho[c], 0.02f * rho[c] * rho[c]) << name << " channel " << c;
    }
  }
}

/// A plane at height 0.5 whose 4 x 4 mask squares alternate open and opaque, over a floor lit by a small light at
/// height 3: under an open square the floor gets the unshadowed closed form, under an opaque one nothing, in both
/// back-ends; a camera ray through an open square reaches the floor.
class Cutout : public ::testing::TestWithParam<AccelKind> {};

TEST_P(Cutout, ShadowHasExactlyTheMaskHoles) {
  if (GetParam() == AccelKind::kEmbree && !embree_available()) GTEST_SKIP() << "this build has no Embree";
  const Vec3 rho(0.5f), le(400.0f);
  const float light_half = 0.01f, light_height = 3.0f;
  Scene s = test::make_rect_light_over_floor(2 * light_half, 2 * light_half, light_height, rho, le);
  Material leaf;
  leaf.name = "leaf";
  leaf.kd = Vec3(0.3f);
  leaf.alpha_texture = 0;
  s.materials.push_back(leaf);
  s.textures = {make_texture(8, 8, [](int x, int y) {
    const bool open = (x / 2 + y / 2) % 2 == 1;
    return std::array<uint8_t, 4>{40, 120, 40, static_cast<uint8_t>(open ? 0 : 255)};
  })};
  add_textured_quad(s, {-1, 0.5f, 1}, {1, 0.5f, 1}, {1, 0.5f, -1}, {-1, 0.5f, -1}, 2);  // v runs toward -z
  const auto traced = prepare_scene(std::move(s), GetParam());

  DirectLightOptions options;
  options.rays = 64;
  options.blinn_k = 1.0f;
  const std::vector<glm::dvec3> light = {{-light_half, light_height, -light_half},
                                         {light_half, light_height, -light_half},
                                         {light_half, light_height, light_half},
                                         {-light_half, light_height, light_half}};
  int open_squares = 0;
  for (int sy = 0; sy < 4; ++sy)
    for (int sx = 0; sx < 4; ++sx) {
      const bool open = (sx + sy) % 2 == 1;  // mask rows from the top are rows toward -z
      // The square's centre on the floor; the light is small and far enough that every shadow ray from it crosses
      // the plane inside the same square.
      const Vec3 floor_point(-1.0f + 0.5f * (sx + 0.5f), 0.0f, -1.0f + 0.5f * (sy + 0.5f));
      const std::optional<SurfacePoint> sp = test::surface_below(*traced, floor_point, 0.25f);
      ASSERT_TRUE(sp);
      PixelSampler sampler(SamplerKind::kIndependent, 7, sy * 4 + sx, 0, RngPurpose::kDirect);
      uint64_t rays = 0;
      const Vec3 l1 = estimate_direct_light(*traced, *sp, options, sampler, 0, rays);
      const double expected =
          rho.r / kPi * test::lambert_irradiance(light, glm::dvec3(sp->position), glm::dvec3(0, 1, 0), le.r);
      if (open) {
        EXPECT_NEAR(l1.r, expected, 0.01 * expected) << "open square " << sx << "," << sy;
        ++open_squares;
      } else {
        EXPECT_EQ(l1.r, 0.0f) << "opaque square " << sx << "," << sy;
      }
      // From above: an open square lets the ray through to the floor, an opaque one stops it on the plane.
      Ray from_above;
      from_above.origin = floor_point + Vec3(0.0f, 2.0f, 0.0f);
      from_above.dir = Vec3(0, -1, 0);
      const Hit hit = intersect_closest(traced->accel, from_above);
      ASSERT_TRUE(hit.found());
      EXPECT_NEAR(hit.t, open ? 2.0f : 1.5f, 1e-5f) << "square " << sx << "," << sy;
      EXPECT_EQ(intersect_any(traced->accel, from_above), true);
      Ray to_plane = from_above;
      to_plane.tmax = 1.75f;  // between the plane and the floor: only an opaque square stops it
      EXPECT_EQ(intersect_any(traced->accel, to_plane), !open) << "square " << sx << "," << sy;
    }
  EXPECT_EQ(open_squares, 8);
}

INSTANTIATE_TEST_SUITE_P(Accel, Cutout, ::testing::Values(AccelKind::kLueur, AccelKind::kEmbree),
                         [](const auto& param) {
                           return std::string(param.param == AccelKind::kLueur ? "Lueur" : "Embree");
                         });

/// Both back-ends agree hit for hit on a scene of many cut-out triangles crossed by random rays.
TEST(Cutout, BackEndsAgreeRayForRay) {
  if (!embree_available()) GTEST_SKIP() << "this build has no Embree";
  Scene s;
  Material leaf;
  leaf.alpha_texture = 0;
  s.materials = {leaf};
  s.textures = {make_texture(16, 16, [](int x, int y) {
    return std::array<uint8_t, 4>{0, 0, 0, static_cast<uint8_t>(((x * 7 + y * 3) % 5) < 2 ? 0 : 255)};
  })};
  Pcg32 rng(11, 0);
  for (int q = 0; q < 40; ++q) {
    const Vec3 c(rng.next_float() * 2 - 1, rng.next_float() * 2 - 1, rng.next_float() * 2 - 1);
    const Vec3 a(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f);
    const Vec3 b(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f);
    add_textured_quad(s, c - a - b, c + a - b, c + a + b, c - a + b, 0);
  }
  const auto lueur = prepare_scene(s, AccelKind::kLueur);
  const auto embree = prepare_scene(s, AccelKind::kEmbree);
  int hits = 0, passed_through = 0;
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    ray.origin = Vec3(rng.next_float() * 6 - 3, rng.next_float() * 6 - 3, 3.0f);
    ray.dir = glm::normalize(Vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, -1.0f));
    const Hit a = intersect_closest(lueur->accel, ray), b = intersect_closest(embree->accel, ray);
    ASSERT_EQ(a.triangle, b.triangle) << "ray " << i;
    if (a.found()) {
      ++hits;
      EXPECT_EQ(a.t, b.t);
      EXPECT_FALSE(lueur->scene.cut_out(a.triangle, a.u, a.v));
    }
    ray.tmax = 4.0f;
    EXPECT_EQ(intersect_any(lueur->accel, ray), intersect_any(embree->accel, ray)) << "ray " << i;
    // Without the mask, how often would a nearer (cut-out) triangle have been hit instead?
    const Hit unfiltered = intersect_closest(lueur->accel.bvh, ray);
    if (unfiltered.found() && unfiltered.triangle != a.triangle) ++passed_through;
  }
  EXPECT_GT(hits, 200);
  EXPECT_GT(passed_through, 50);  // the holes were really crossed
}

// ---- the loader --------------------------------------------------------------------------------------------------

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// A 4 x 4 RGBA PNG whose left half is red and opaque and whose right half is blue and transparent.
void write_rgba_png(const std::string& path) {
  std::vector<uint8_t> texels;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const bool left = x < 2;
      texels.insert(texels.end(), {static_cast<uint8_t>(left ? 255 : 0), 0, static_cast<uint8_t>(left ? 0 : 255),
                                   static_cast<uint8_t>(left ? 255 : 0)});
    }
  ASSERT_TRUE(stbi_write_png(path.c_str(), 4, 4, 4, texels.data(), 16));
}

const char* const kTexturedObj =
    "mtllib quad.mtl\n"
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "usemtl leaf\n"
    "f 1/1 2/2 3/3 4/4\n";

TEST(TextureLoading, MapKdAndMapDAreReadBesideTheMtl) {
  const std::string dir = test::make_temp_dir("textures-load");
  std::filesystem::create_directories(dir + "/maps");
  write_rgba_png(dir + "/maps/leaf.png");
  write_text(dir + "/quad.obj", kTexturedObj);
  write_text(dir + "/quad.mtl", "newmtl leaf\nKd 1 1 1\nmap_Kd maps\\leaf.png\nmap_d -clamp off maps/leaf.png\n");
  const LoadedScene loaded = load_obj(dir + "/quad.obj");
  const Scene& s = loaded.scene;
  ASSERT_EQ(s.textures.size(), 1u) << "one file used twice is read once";
  EXPECT_EQ(s.textures[0].width, 4);
  EXPECT_TRUE(s.textures[0].has_alpha);
  ASSERT_EQ(s.texcoords.size(), 4u);
  const Material& m = s.materials[0];
  EXPECT_EQ(m.diffuse_texture, 0);
  EXPECT_EQ(m.alpha_texture, 0);
  // Triangle 0 is (1 2 3): u weights corner 2 (texcoord (1, 0)), v corner 3 (1, 1), so texture u = u + v. Texture
  // u 0.25 lies between the two red columns' centres, 0.75 between the two blue ones'.
  EXPECT_EQ(s.albedo(0, 0.2f, 0.05f), Vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(s.albedo(0, 0.7f, 0.05f), Vec3(0.0f, 0.0f, 1.0f));
  EXPECT_FALSE(s.cut_out(0, 0.2f, 0.05f));
  EXPECT_TRUE(s.cut_out(0, 0.7f, 0.05f));
  for (const std::string& w : loaded.warnings) EXPECT_EQ(w.find("map_"), std::string::npos) << w;
}

TEST(TextureLoading, JpegColourMapsAreDecoded) {
  const std::string dir = test::make_temp_dir("textures-jpeg");
  // A uniform 16 x 16 JPEG (quality 100): its decoded texels are the colour within a few levels.
  std::vector<uint8_t> orange;
  for (int i = 0; i < 16 * 16; ++i) orange.insert(orange.end(), {230, 120, 30});
  ASSERT_TRUE(stbi_write_jpg((dir + "/orange.jpg").c_str(), 16, 16, 3, orange.data(), 100));
  write_text(dir + "/quad.obj", kTexturedObj);
  write_text(dir + "/quad.mtl", "newmtl leaf\nmap_Kd orange.jpg\n");
  const LoadedScene loaded = load_obj(dir + "/quad.obj");
  ASSERT_EQ(loaded.scene.textures.size(), 1u);
  EXPECT_FALSE(loaded.scene.textures[0].has_alpha);
  const Vec3 albedo = loaded.scene.albedo(0, 0.3f, 0.3f);
  EXPECT_NEAR(albedo.r, linear_of(230), 0.02f);
  EXPECT_NEAR(albedo.g, linear_of(120), 0.02f);
  EXPECT_NEAR(albedo.b, linear_of(30), 0.01f);
}

TEST(TextureLoading, MissingAndHostileImagesAreOneWarningAndGrey) {
  const std::string dir = test::make_temp_dir("textures-hostile");
  write_text(dir + "/quad.obj", kTexturedObj);
  // Not an image; a PNG cut short after its header; a PNG header claiming 2^30 x 2^30 texels.
  write_text(dir + "/text.png", "this is not an image\n");
  write_rgba_png(dir + "/whole.png");
  const std::string whole = test::read_file(dir + "/whole.png");
  write_text(dir + "/truncated.png", whole.substr(0, 40));
  std::string huge = whole.substr(0, 33);
  huge[16] = 0x40, huge[17] = 0, huge[18] = 0, huge[19] = 0;  // width 2^30 (big-endian)
  huge[20] = 0x40, huge[21] = 0, huge[22] = 0, huge[23] = 0;  // height 2^30
  write_text(dir + "/huge.png", huge);
  for (const std::string image : {"absent.png", "text.png", "truncated.png", "huge.png"}) {
    write_text(dir + "/quad.mtl", "newmtl leaf\nKd 0.9 0.1 0.1\nmap_Kd " + image + "\nmap_d " + image + "\n");
    const LoadedScene loaded = load_obj(dir + "/quad.obj");
    EXPECT_TRUE(loaded.scene.textures.empty()) << image;
    const Material& m = loaded.scene.materials[0];
    EXPECT_EQ(m.kd, Vec3(0.5f)) << image << ": a missing colour map falls back to grey";
    EXPECT_EQ(m.alpha_texture, -1) << image << ": a missing mask cuts nothing";
    int texture_warnings = 0;
    for (const std::string& w : loaded.warnings)
      if (w.find(image) != std::string::npos) {
        ++texture_warnings;
        EXPECT_EQ(w.find('\n'), std::string::npos) << w;
      }
    EXPECT_EQ(texture_warnings, 1) << image << ": said once, although named by map_Kd and map_d";
  }
}

TEST(TextureLoading, TexturesCountInTheMemoryBudget) {
  const std::string dir = test::make_temp_dir("textures-budget");
  write_rgba_png(dir + "/leaf.png");
  write_text(dir + "/quad.obj", kTexturedObj);
  write_text(dir + "/quad.mtl", "newmtl leaf\nmap_Kd leaf.png\n");
  const uint64_t scene_bytes = scene_memory_bytes(std::string(kTexturedObj).size(), 4, 0, 4, 2);
  LoadOptions options;
  options.memory = MemoryBudget{scene_bytes + 1000, "a test's budget"};
  EXPECT_EQ(load_obj(dir + "/quad.obj", options).scene.textures.size(), 1u);  // 64 bytes of texels fit in 1000
  options.memory = MemoryBudget{scene_bytes + 40, "a test's budget"};
  const LoadedScene refused = load_obj(dir + "/quad.obj", options);
  EXPECT_TRUE(refused.scene.textures.empty());
  bool said = false;
  for (const std::string& w : refused.warnings) said |= w.find("left for textures") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(TextureLoading, ManyTexturesOnManyThreadsFitTheBudgetAsOneThreadWouldRead) {
  // Ten quads, each with its own 4 x 4 colour map (64 bytes of texels). The fourth map's header reads but its image
  // does not decode: the budget (five maps and 128 bytes more) must then let the seventh map in, exactly as reading
  // the files one after the other does, whatever the threads and however the files are shared out among them.
  const std::string dir = test::make_temp_dir("textures-many");
  std::string obj = "mtllib many.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  std::string mtl;
  write_rgba_png(dir + "/whole.png");
  const std::string whole = test::read_file(dir + "/whole.png");
  ASSERT_LT(whole.size(), 128u) << "the budget below assumes small files";
  for (int i = 0; i < 10; ++i) {
    const std::string file = "map" + std::to_string(i) + ".png";
    write_text(dir + "/" + file, i == 3 ? whole.substr(0, 40) : whole);  // 40 bytes: the header and no image
    mtl += "newmtl m" + std::to_string(i) + "\nKd 1 1 1\nmap_Kd " + file + "\n";
    const float x = static_cast<float>(3 * i);
    obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + 1) + " 0 0\nv " + std::to_string(x + 1) +
           " 1 0\nv " + std::to_string(x) + " 1 0\nusemtl m" + std::to_string(i) + "\nf -4/1 -3/2 -2/3 -1/4\n";
  }
  write_text(dir + "/many.obj", obj);
  write_text(dir + "/many.mtl", mtl);
  LoadOptions options;
  options.light_rig = false;
  options.memory = MemoryBudget{scene_memory_bytes(obj.size(), 40, 0, 4, 20) + 5 * 64 + 128, "a test's budget"};

  std::vector<std::string> one_thread_warnings;
  for (const unsigned threads : {1u, 2u, 3u, 8u}) {
    SCOPED_TRACE(threads);
    options.threads = threads;
    const LoadedScene loaded = load_obj(dir + "/many.obj", options);
    const Scene& scene = loaded.scene;
    ASSERT_EQ(scene.textures.size(), 6u);
    // Maps 0, 1, 2, 4, 5 and 6 are read, in that order; 3 does not decode; 7, 8 and 9 find no room left.
    const int expected[10] = {0, 1, 2, -1, 3, 4, 5, -1, -1, -1};
    for (int i = 0; i < 10; ++i) {
      const auto material = std::find_if(scene.materials.begin(), scene.materials.end(),
                                         [&](const Material& m) { return m.name == "m" + std::to_string(i); });
      ASSERT_NE(material, scene.materials.end());
      EXPECT_EQ(material->diffuse_texture, expected[i]) << "map " << i;
      if (expected[i] >= 0) {
        EXPECT_EQ(scene.textures[static_cast<size_t>(expected[i])].name, "map" + std::to_string(i) + ".png");
      }
    }
    std::vector<std::string> texture_warnings;
    for (const std::string& w : loaded.warnings)
      if (w.find("map_Kd") != std::string::npos) texture_warnings.push_back(w);
    ASSERT_EQ(texture_warnings.size(), 4u);
    EXPECT_NE(texture_warnings[0].find("'map3.png': could not be decoded"), std::string::npos) << texture_warnings[0];
    EXPECT_NE(texture_warnings[1].find("'map7.png': a "), std::string::npos) << texture_warnings[1];
    EXPECT_NE(texture_warnings[1].find("more than the 64 bytes left for textures"), std::string::npos)
        << texture_warnings[1];
    if (threads == 1) one_thread_warnings = texture_warnings;
    EXPECT_EQ(texture_warnings, one_thread_warnings);
  }
}

}  // namespace
}  // namespace lueur
