// libFuzzer target: OBJ + MTL text all the way to a rendered 16x16 frame, the path a scene from the internet
// takes. Input: the OBJ text, optionally followed by a line "#mtl" and the MTL text that its mtllib stands for
// ("#mtl" is an OBJ comment, so any OBJ file is a valid input as it is), optionally followed by a line "#image" and
// the bytes of an image file (PNG, JPEG, ...): decoded as a texture file would be, it becomes the colour map and the
// cutout mask of every material that names a map_Kd or map_d, so that image decoding, texture sampling and the
// traversals' cutout filter all meet hostile data. A few input-derived bits pick the light strategy, reuse mode and
// normals, so every branch of the renderer is reachable.
// Refusal (SceneError) is a correct outcome; any other exception, a crash, a sanitizer report, a leak, a hang
// or a non-finite value in the film is a finding. Run it with scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "image/image_output.h"
#include "core/camera.h"
#include "film/film.h"
#include "integrator/renderer.h"
#include "core/thread_pool.h"
#include "integrator/traced_scene.h"
#include "scene/obj_loader.h"
#include "scene/texture.h"

namespace {

using namespace lueur;

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 1469598103934665603ull;
  for (const char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

/// Stops the run as a finding, with a line that says what was wrong.
[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_scene_to_frame: %s\n", what);
  __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string_view image_bytes;
  if (const size_t at = input.find("\n#image\n"); at != std::string_view::npos) {
    image_bytes = input.substr(at + 8);
    input = input.substr(0, at + 1);
  }
  std::string_view obj = input, mtl;
  if (input.substr(0, 5) == "#mtl\n") {
    obj = {};
    mtl = input.substr(5);
  } else if (const size_t at = input.find("\n#mtl\n"); at != std::string_view::npos) {
    obj = input.substr(0, at + 1);
    mtl = input.substr(at + 6);
  }
  const uint64_t bits = fnv1a(input);

  LoadOptions load;
  load.smooth_normals = (bits & 1) != 0;
  load.memory = MemoryBudget{uint64_t{256} << 20, "the fuzzer's budget"};
  LoadedScene loaded;
  try {
    loaded = load_obj_from_text(std::string(obj), std::string(mtl), "fuzz.obj", load);
  } catch (const SceneError&) {
    return 0;  // refused with a message: a correct outcome
  }

  // The image stands for every texture file the materials name (loading from text reads no file).
  Texture texture;
  if (!image_bytes.empty() && decode_texture(std::string(image_bytes), uint64_t{16} << 20, texture).empty()) {
    Scene& scene = loaded.scene;
    scene.textures.push_back(std::move(texture));
    for (Material& m : scene.materials) {
      if (!m.diffuse_map.empty()) m.diffuse_texture = 0, m.kd = Vec3(1.0f);
      if (!m.alpha_map.empty()) m.alpha_texture = 0;
    }
  }

  RenderSettings settings;
  settings.width = settings.height = 16;
  settings.enabled = {true, true, true, true, true};
  settings.lights = static_cast<LightStrategy>((bits >> 1) % 4);
  settings.reuse = static_cast<ReuseMode>((bits >> 3) % 3);
  settings.reuse_diffuse_only = ((bits >> 5) & 1) != 0;
  settings.blinn_k = static_cast<float>((bits >> 6) % 5) * 0.25f;
  settings.l1_rays = settings.l2_rays = settings.ao_rays = settings.ln_rays = 2;
  settings.max_bounces = 1 + static_cast<int>((bits >> 9) % 8);  // the camera's mirrors and glass, and ln's paths
  settings.seed = bits >> 32;

  const std::shared_ptr<const TracedScene> traced = prepare_scene(std::move(loaded.scene));
  const Camera camera = make_camera(frame_box(traced->scene.bounds(), 45.0f, 1.0f), settings.width, settings.height);
  static ThreadPool pool(1);
  Film film;
  film.reset(settings);
  for (int frame = 0; frame < 2; ++frame) render_frame(*traced, camera, settings, film, nullptr, pool);

  for (const std::vector<float>& sums : film.sums)
    for (const float v : sums)
      if (!std::isfinite(v)) finding("non-finite value in the film");
  const Image image = combine_passes(film, settings.enabled, kReportWeights);
  if (encode_png(image, DisplaySettings{}, "fuzz").size() < 8) finding("empty PNG");
  return 0;
}
