// The buffer sizes of render_frame, Film and write_image, per pixel.
#include "runtime/render_memory.h"

#include <algorithm>

#include "film/film.h"
#include "integrator/indirect_light.h"
#include "integrator/traced_scene.h"

namespace lueur {

uint64_t render_memory_bytes(const RenderSettings& settings) {
  const uint64_t pixels =
      static_cast<uint64_t>(std::max(settings.width, 0)) * static_cast<uint64_t>(std::max(settings.height, 0));
  const std::array<bool, kLayerCount> needed = layers_needed(settings);
  const uint64_t layers = static_cast<uint64_t>(std::count(needed.begin(), needed.end(), true));
  constexpr uint64_t kRgb = 3 * sizeof(float);

  // The film: its layers (exact and float sums), and the noise estimate's snapshots of the passes.
  const uint64_t passes = static_cast<uint64_t>(std::count(settings.enabled.begin(), settings.enabled.end(), true));
  const uint64_t film = layers * (kRgb + 3 * sizeof(int64_t)) + kNoiseCheckpoints * passes * kRgb;
  // render_frame: per-layer values, the primary hits and the screen buffer L2 reuses.
  // The L1 store: its cap, and a frame's records waiting for the merge (one per pixel and per recomputed bounce hit).
  const bool store = settings.pass_enabled(Pass::kL2) && uses_cache(settings.reuse);
  const uint64_t store_bytes = store ? static_cast<uint64_t>(std::max(settings.cache_mb, 0)) << 20 : 0;
  const uint64_t records =
      store ? (1 + static_cast<uint64_t>(std::max(settings.l2_rays, 0))) * sizeof(L1CacheRecord) : 0;
  const uint64_t frame = layers * sizeof(Vec3) + sizeof(SurfacePoint) + sizeof(uint32_t) + 4 * sizeof(Vec3) + records;
  // Saving: every layer averaged, the shown image, and the EXR channel planes, its encoder's copy and its output.
  const uint64_t output = layers * kRgb + kRgb + 3 * (layers + 1) * kRgb;
  constexpr uint64_t kProcess = uint64_t{64} << 20;  // code, thread stacks, allocator slack
  return pixels * (film + std::max(frame, output)) + store_bytes + kProcess;
}

}  // namespace lueur
