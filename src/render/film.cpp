// Averages and the weighted combination of the per-pass sums.
#include "render/film.h"

#include <algorithm>

namespace lueur {

void Film::reset(int new_width, int new_height, const std::array<bool, kLayerCount>& layers) {
  width = new_width;
  height = new_height;
  frames = 0;
  for (int l = 0; l < kLayerCount; ++l) {
    auto& sum = sums[static_cast<size_t>(l)];
    if (layers[static_cast<size_t>(l)])
      sum.assign(3 * pixel_count(), 0.0f);
    else
      sum.clear();
  }
  l1_cache.reset(0);
  for (PassSnapshot& checkpoint : checkpoints) {
    checkpoint.frames = 0;
    for (auto& pass : checkpoint.sums) pass.clear();
  }
}

void Film::finish_frame() {
  ++frames;
  if ((frames & (frames - 1)) != 0) return;
  // The oldest snapshot's buffers are reused for the newest.
  std::rotate(checkpoints.rbegin(), checkpoints.rbegin() + 1, checkpoints.rend());
  PassSnapshot& newest = checkpoints.front();
  newest.frames = frames;
  for (int p = 0; p < kPassCount; ++p) {
    const auto& sum = sums[static_cast<size_t>(layer_of(static_cast<Pass>(p)))];
    newest.sums[static_cast<size_t>(p)].assign(sum.begin(), sum.end());
  }
}

void Film::reset(const RenderSettings& settings) {
  reset(settings.width, settings.height, layers_needed(settings));
  if (settings.pass_enabled(Pass::kL2) && uses_cache(settings.reuse))
    l1_cache.reset(static_cast<uint64_t>(std::max(settings.cache_mb, 0)) << 20);
}

Image layer_average(const Film& film, Layer layer) {
  Image image{film.width, film.height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  const auto& sum = film.sums[static_cast<size_t>(layer)];
  if (sum.empty() || film.frames == 0) return image;
  const float scale = 1.0f / static_cast<float>(film.frames);
  for (size_t i = 0; i < sum.size(); ++i) image.rgb[i] = sum[i] * scale;
  return image;
}

Image combine_passes(const Film& film, const std::array<bool, kPassCount>& enabled,
                     const std::array<float, kPassCount>& weights) {
  Image image{film.width, film.height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  if (film.frames == 0) return image;
  for (int p = 0; p < kPassCount; ++p) {
    const auto& sum = film.sums[static_cast<size_t>(p)];
    if (!enabled[static_cast<size_t>(p)] || sum.empty()) continue;
    const float scale = weights[static_cast<size_t>(p)] / static_cast<float>(film.frames);
    for (size_t i = 0; i < sum.size(); ++i) image.rgb[i] += sum[i] * scale;
  }
  return image;
}

}  // namespace lueur
