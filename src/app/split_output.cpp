// Column-wise composition; the divider goes only into the 8-bit PNG, never into the linear PFM or EXR data.
#include "app/split_output.h"

#include <algorithm>
#include <filesystem>

#include "app/displayed_image.h"
#include "core/atomic_file.h"
#include "display/split_view.h"
#include "image/image_output.h"
#include "settings/compare.h"

namespace lueur {

Image split_image(const Image& left, const Image& right, int column) {
  Image split = left;
  for (int y = 0; y < split.height; ++y) {
    const size_t row = 3 * static_cast<size_t>(y) * static_cast<size_t>(split.width);
    std::copy(right.rgb.begin() + static_cast<std::ptrdiff_t>(row + 3 * static_cast<size_t>(column)),
              right.rgb.begin() + static_cast<std::ptrdiff_t>(row + 3 * static_cast<size_t>(split.width)),
              split.rgb.begin() + static_cast<std::ptrdiff_t>(row + 3 * static_cast<size_t>(column)));
  }
  return split;
}

void write_split_image(const std::string& path, const Film& left, const Film& right, const Settings& shown,
                       const std::string& metadata) {
  const Settings right_shown = compared_settings(shown).value_or(shown);
  const int column = split_column(shown.compare_split, left.width);
  const Image image = split_image(displayed_image(left, shown), displayed_image(right, right_shown), column);
  if (std::filesystem::path(path).extension() == ".png") {
    std::vector<uint8_t> rgb = tonemap_to_rgb8(image, displayed_transform(shown));
    const int x0 = std::clamp(column - kDividerWidth / 2, 0, std::max(left.width - kDividerWidth, 0));
    for (int y = 0; y < left.height; ++y)
      for (int x = x0; x < std::min(x0 + kDividerWidth, left.width); ++x)
        for (size_t c = 0; c < 3; ++c)
          rgb[3 * (static_cast<size_t>(y) * static_cast<size_t>(left.width) + static_cast<size_t>(x)) + c] = 230;
    write_file_atomically(path, encode_png_rgb8(rgb, left.width, left.height, metadata));
    return;
  }
  std::vector<NamedImage> layers;
  const std::vector<NamedImage> right_layers = film_layer_images(right);
  for (const NamedImage& layer : film_layer_images(left))
    for (const NamedImage& other : right_layers)
      if (other.name == layer.name) layers.push_back({layer.name, split_image(layer.image, other.image, column)});
  write_image(path, image, layers, displayed_transform(shown), metadata);
}

}  // namespace lueur
