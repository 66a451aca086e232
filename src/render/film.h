// The accumulation buffers: one float RGB sum per pass plus the frame count, and the image they average to; and the
// L1 store, which accumulates with them. Depends on render settings and the L1 store.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "render/l1_cache.h"
#include "render/settings.h"

namespace lueur {

/// A linear float RGB image, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< 3 x width x height
  Vec3 at(int x, int y) const {
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return Vec3(rgb[i], rgb[i + 1], rgb[i + 2]);
  }
};

/// The pass sums as they stood after `frames` frames (empty when the pass is not rendered or frames is 0).
struct PassSnapshot {
  uint64_t frames = 0;
  std::array<std::vector<float>, kPassCount> sums;
};

/// How many snapshots the film keeps for the noise estimate (render/noise_estimate.h): at the last four powers of
/// two of its frame count.
inline constexpr int kNoiseCheckpoints = 4;

struct Film {
  int width = 0, height = 0;
  std::array<std::vector<float>, kLayerCount> sums;  ///< per layer, 3 x width x height; empty when not rendered
  uint64_t frames = 0;
  L1Cache l1_cache;  ///< empty, with no room, unless the settings' reuse mode uses it
  /// The pass sums when the frame count was last a power of two N, then at N/2, N/4 and N/8 (frames 0: none yet).
  std::array<PassSnapshot, kNoiseCheckpoints> checkpoints;

  /// Sizes the buffers for the layers these settings need and clears everything (the L1 store with no room).
  void reset(int new_width, int new_height, const std::array<bool, kLayerCount>& layers);
  void reset(const RenderSettings& settings);
  size_t pixel_count() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  bool has(Layer l) const { return !sums[static_cast<size_t>(l)].empty(); }
  bool has(Pass p) const { return has(layer_of(p)); }
  /// Counts a frame whose values are in the sums, and snapshots the pass sums when the count becomes a power of two.
  void finish_frame();
};

/// The running average of one layer (black if the layer has no samples).
Image layer_average(const Film& film, Layer layer);
inline Image pass_average(const Film& film, Pass pass) { return layer_average(film, layer_of(pass)); }

/// sum over enabled passes of weight x average(pass).
Image combine_passes(const Film& film, const std::array<bool, kPassCount>& enabled,
                     const std::array<float, kPassCount>& weights);

/// What a display shows of the film: the average of `layer` when one is chosen, else the weighted combination.
inline Image shown_image(const Film& film, const std::array<bool, kPassCount>& enabled,
                         const std::array<float, kPassCount>& weights, const std::optional<Layer>& layer) {
  return layer ? layer_average(film, *layer) : combine_passes(film, enabled, weights);
}

}  // namespace lueur
