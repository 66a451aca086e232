// Framebuffer object set-up and read-back.
#include "display/offscreen_target.h"

#include <cstring>
#include <stdexcept>

namespace lueur {

OffscreenTarget::OffscreenTarget(const GlApi& gl, int width, int height) : gl_(gl), width_(width), height_(height) {
  gl_.GenTextures(1, &color_);
  gl_.BindTexture(GL_TEXTURE_2D, color_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
  const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    gl_.DeleteFramebuffers(1, &framebuffer_);
    gl_.DeleteTextures(1, &color_);
    throw std::runtime_error("off-screen framebuffer is incomplete (status " + std::to_string(status) + ")");
  }
}

OffscreenTarget::~OffscreenTarget() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.DeleteFramebuffers(1, &framebuffer_);
  gl_.DeleteTextures(1, &color_);
}

void OffscreenTarget::bind() const { gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

std::vector<uint8_t> OffscreenTarget::read_rgb8() const {
  const size_t w = static_cast<size_t>(width_), h = static_cast<size_t>(height_);
  std::vector<uint8_t> rgba(4 * w * h);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.Finish();
  gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  std::vector<uint8_t> rgb(3 * w * h);
  for (size_t y = 0; y < h; ++y) {
    const uint8_t* src = rgba.data() + 4 * w * (h - 1 - y);
    uint8_t* dst = rgb.data() + 3 * w * y;
    for (size_t x = 0; x < w; ++x) std::memcpy(dst + 3 * x, src + 4 * x, 3);
  }
  return rgb;
}

}  // namespace lueur
