// The GPU half of the display: the tracer's per-pass sums as float textures, combined by the shaders in shaders/
// (weighted sum, exposure, tone map, sRGB) into whatever framebuffer is bound: a window's or an off-screen one.
// Weights, exposure and tone map are uniforms, so changing them never touches the accumulation.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "display/gl_api.h"
#include "film/film.h"
#include "film/tonemap.h"
#include "settings/settings.h"

namespace lueur {

/// A rectangle in framebuffer pixels, origin bottom-left as GL has it.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

class DisplayPipeline {
 public:
  /// Compiles and links the display program. Throws std::runtime_error with the GL log on failure.
  explicit DisplayPipeline(const GlApi& gl);
  ~DisplayPipeline();
  DisplayPipeline(const DisplayPipeline&) = delete;
  DisplayPipeline& operator=(const DisplayPipeline&) = delete;

  /// Uploads the layers the settings show (their passes, or their layer) from `film`, skipping textures that already
  /// hold that layer of the same `film_version` (a number the caller changes whenever the film's contents change).
  void update(const Film& film, uint64_t film_version, const Settings& shown);

  /// Draws the last uploaded film as `shown` says (weights, layer, exposure, tone map: none restarts the tracer) into
  /// `image` of the bound framebuffer, whose full size is `viewport` (pixels outside the image are black).
  /// With `clip`, only the pixels inside it are drawn (an A/B split's side).
  void draw(const Settings& shown, const PixelRect& viewport, const PixelRect& image,
            const std::optional<PixelRect>& clip = std::nullopt) const;

  int film_width() const { return width_; }
  uint64_t film_frames() const { return frames_; }
  int film_height() const { return height_; }

 private:
  struct Slot {
    unsigned texture = 0;
    int layer = -1;  ///< which film layer it holds, -1 none, kNoiseView the noise view
    uint64_t version = 0;
    uint64_t key = 0;  ///< for the noise view: a hash of the weights it was made with
    int width = 0, height = 0;
  };
  static constexpr int kNoiseView = -2;
  std::array<int, 4> slot_layers(const Settings& shown) const;
  void upload(Slot& slot, const float* rgb, int width, int height);

  const GlApi& gl_;
  unsigned program_ = 0, vertex_array_ = 0;
  struct Uniforms {
    int scale = -1, exposure = -1, tonemap = -1, rect = -1;
  } uniforms_;  ///< looked up once: the program never changes
  std::array<Slot, 4> slots_;
  std::array<bool, kLayerCount> film_has_{};
  uint64_t frames_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace lueur
