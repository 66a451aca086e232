// The accumulation buffers: one float RGB sum per pass plus the frame count, and the image they average to.
// Depends on render settings only.
#pragma once

#include "render/settings.h"

#include <array>
#include <vector>

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

struct Film {
  int width = 0, height = 0;
  std::array<std::vector<float>, kPassCount> sums;  ///< per pass, 3 x width x height; empty when never enabled
  uint64_t frames = 0;

  /// Sizes the buffers for the enabled passes and clears everything.
  void reset(int new_width, int new_height, const std::array<bool, kPassCount>& enabled);
  size_t pixel_count() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  bool has(Pass p) const { return !sums[static_cast<size_t>(p)].empty(); }
};

/// The running average of one pass (black if the pass has no samples).
Image pass_average(const Film& film, Pass pass);

/// sum over enabled passes of weight x average(pass).
Image combine_passes(const Film& film, const std::array<bool, kPassCount>& enabled,
                     const std::array<float, kPassCount>& weights);

}  // namespace lueur
