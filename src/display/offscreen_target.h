// An off-screen framebuffer (RGBA8 colour texture) that the display draws into and reads back from: the headless
// screenshot path through the real shaders.
#pragma once

#include <cstdint>
#include <vector>

#include "display/gl_api.h"

namespace lueur {

class OffscreenTarget {
 public:
  /// Throws std::runtime_error when the framebuffer is incomplete.
  OffscreenTarget(const GlApi& gl, int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  void bind() const;
  /// Waits for the GPU and returns RGB8 pixels, rows top to bottom (GL's bottom-up rows flipped).
  std::vector<uint8_t> read_rgb8() const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  const GlApi& gl_;
  int width_, height_;
  unsigned framebuffer_ = 0, color_ = 0;
};

}  // namespace lueur
