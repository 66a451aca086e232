#include "passes/render_settings.h"

namespace lueur {

std::array<bool, kLayerCount> layers_needed(const RenderSettings& settings) {
  std::array<bool, kLayerCount> needed{};
  for (int p = 0; p < kPassCount; ++p) needed[static_cast<size_t>(p)] = settings.enabled[static_cast<size_t>(p)];
  if (settings.pass_enabled(Pass::kL2)) {
    if (settings.reuse == ReuseMode::kAverage)
      needed[static_cast<size_t>(settings.reuse_diffuse_only ? Layer::kL1Diffuse : Layer::kL1)] = true;
    needed[static_cast<size_t>(Layer::kL2Reused)] = true;
    needed[static_cast<size_t>(Layer::kL2Recomputed)] = true;
    needed[static_cast<size_t>(Layer::kReuseFraction)] = true;
    if (uses_cache(settings.reuse)) {
      needed[static_cast<size_t>(Layer::kL2Cached)] = true;
      needed[static_cast<size_t>(Layer::kCacheCells)] = true;
    }
  }
  return needed;
}

}  // namespace lueur
