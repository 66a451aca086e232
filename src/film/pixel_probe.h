// One pixel of a film read out for the window's pixel inspector: what each rendered layer holds there and the
// combination the image shows, so that a user can watch a pixel's L1 and L2 converge. Depends on the film.
#pragma once

#include <array>
#include <optional>

#include "film/film.h"

namespace lueur {

/// A pixel of a film, rows top to bottom.
struct FilmPixel {
  int x = 0, y = 0;
  bool operator==(const FilmPixel&) const = default;
};

/// The film pixel under the point (x, y) of a view that shows the whole film stretched over view_width x
/// view_height (window coordinates, y down, as the display draws it); nullopt outside the view or for an empty one.
std::optional<FilmPixel> film_pixel_at(double x, double y, double view_width, double view_height, int film_width,
                                       int film_height);

struct PixelProbe {
  FilmPixel pixel;
  uint64_t frames = 0;
  std::array<std::optional<Vec3>, kLayerCount> layers;  ///< each rendered layer's running average there
  Vec3 combined{0.0f};  ///< sum over the enabled passes of weight x average: the image's linear value there
};

/// Reads a pixel of `film`: the values layer_average and combine_passes give there. Nullopt outside the film or
/// before its first frame.
std::optional<PixelProbe> probe_pixel(const Film& film, FilmPixel pixel, const std::array<bool, kPassCount>& enabled,
                                      const std::array<float, kPassCount>& weights);

}  // namespace lueur
