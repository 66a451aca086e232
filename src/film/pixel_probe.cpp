// Reading one pixel of a film (see pixel_probe.h).
#include "film/pixel_probe.h"

#include <algorithm>
#include <cmath>

namespace lueur {

std::optional<FilmPixel> film_pixel_at(double x, double y, double view_width, double view_height, int film_width,
                                       int film_height) {
  if (!(view_width > 0.0 && view_height > 0.0) || film_width <= 0 || film_height <= 0) return std::nullopt;
  if (!(x >= 0.0 && x < view_width && y >= 0.0 && y < view_height)) return std::nullopt;  // NaN too
  const int px = static_cast<int>(std::floor(x * film_width / view_width));
  const int py = static_cast<int>(std::floor(y * film_height / view_height));
  return FilmPixel{std::min(px, film_width - 1), std::min(py, film_height - 1)};
}

std::optional<PixelProbe> probe_pixel(const Film& film, FilmPixel pixel, const std::array<bool, kPassCount>& enabled,
                                      const std::array<float, kPassCount>& weights) {
  if (film.frames == 0 || pixel.x < 0 || pixel.y < 0 || pixel.x >= film.width || pixel.y >= film.height)
    return std::nullopt;
  PixelProbe probe;
  probe.pixel = pixel;
  probe.frames = film.frames;
  const size_t i = 3 * (static_cast<size_t>(pixel.y) * static_cast<size_t>(film.width) + static_cast<size_t>(pixel.x));
  const auto value = [&](size_t layer, float scale) {
    const std::vector<float>& sum = film.sums[layer];
    return Vec3(sum[i] * scale, sum[i + 1] * scale, sum[i + 2] * scale);
  };
  // The same float arithmetic, in the same order, as layer_average and combine_passes.
  for (size_t l = 0; l < static_cast<size_t>(kLayerCount); ++l)
    if (!film.sums[l].empty()) probe.layers[l] = value(l, 1.0f / static_cast<float>(film.frames));
  for (size_t p = 0; p < static_cast<size_t>(kPassCount); ++p)
    if (enabled[p] && !film.sums[p].empty()) probe.combined += value(p, weights[p] / static_cast<float>(film.frames));
  return probe;
}

}  // namespace lueur
