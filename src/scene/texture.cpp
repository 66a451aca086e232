// Texture sampling and decoding (see texture.h). The only file that calls stb_image.
#include "scene/texture.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>

#include "core/memory_budget.h"

namespace lueur {
namespace {

/// sRGB byte to linear float, once per process: colour maps are stored as sRGB, albedos are linear.
const std::array<float, 256>& srgb_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[static_cast<size_t>(i)] = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

/// The four texels around `uv` and their bilinear weights, repeating the image in both directions.
struct Footprint {
  size_t texel[4];  ///< byte offsets of the texels, in the order of `weight`
  float weight[4];
};

/// The fractional part in [0, 1); non-finite coordinates read as 0 (a hostile vt must not reach an index).
float wrap01(float x) {
  if (!std::isfinite(x)) return 0.0f;
  const float f = x - std::floor(x);
  return f < 1.0f ? f : 0.0f;  // x just below an integer can round up to 1
}

Footprint footprint(const Texture& texture, Vec2 uv) {
  const int w = texture.width, h = texture.height;
  // Texel centres sit at (i + 0.5) / w; image rows run from the top, OBJ's v from the bottom.
  const float x = wrap01(uv.x) * static_cast<float>(w) - 0.5f;
  const float y = (1.0f - wrap01(uv.y)) * static_cast<float>(h) - 0.5f;
  const float x_floor = std::floor(x), y_floor = std::floor(y);
  const float fx = x - x_floor, fy = y - y_floor;
  auto wrap = [](int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); };
  const int x0 = wrap(static_cast<int>(x_floor), w), x1 = wrap(static_cast<int>(x_floor) + 1, w);
  const int y0 = wrap(static_cast<int>(y_floor), h), y1 = wrap(static_cast<int>(y_floor) + 1, h);
  auto offset = [w](int px, int py) {
    return 4 * (static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px));
  };
  return {{offset(x0, y0), offset(x1, y0), offset(x0, y1), offset(x1, y1)},
          {(1.0f - fx) * (1.0f - fy), fx * (1.0f - fy), (1.0f - fx) * fy, fx * fy}};
}

}  // namespace

Vec3 sample_albedo(const Texture& texture, Vec2 uv) {
  if (texture.rgba.empty()) return Vec3(0.5f);
  const std::array<float, 256>& linear = srgb_to_linear_table();
  const Footprint f = footprint(texture, uv);
  Vec3 sum(0.0f);
  for (int k = 0; k < 4; ++k) {
    const uint8_t* t = &texture.rgba[f.texel[k]];
    sum += f.weight[k] * Vec3(linear[t[0]], linear[t[1]], linear[t[2]]);
  }
  return sum;
}

float sample_coverage(const Texture& texture, Vec2 uv) {
  if (texture.rgba.empty()) return 1.0f;
  const size_t channel = texture.has_alpha ? 3 : 0;
  const Footprint f = footprint(texture, uv);
  float sum = 0.0f;
  for (int k = 0; k < 4; ++k) sum += f.weight[k] * static_cast<float>(texture.rgba[f.texel[k] + channel]);
  return sum * (1.0f / 255.0f);
}

std::string probe_texture(const std::string& bytes, int& width, int& height) {
  if (bytes.size() > static_cast<size_t>(std::numeric_limits<int>::max())) return "too large a file";
  int channels = 0;
  // The header only: a hostile file claiming a huge image is refused before anything is allocated.
  if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &width,
                             &height, &channels))
    return std::string("not a readable image (") + stbi_failure_reason() + ")";
  return {};
}

uint64_t texel_bytes(int width, int height) {
  return 4 * static_cast<uint64_t>(std::max(width, 0)) * static_cast<uint64_t>(std::max(height, 0));
}

std::string check_texture_size(int width, int height, uint64_t byte_limit) {
  if (width <= 0 || height <= 0 || texel_bytes(width, height) > byte_limit)
    return "a " + std::to_string(width) + "x" + std::to_string(height) + " image needs " +
           format_bytes(texel_bytes(width, height)) + ", more than the " + format_bytes(byte_limit) +
           " left for textures";
  return {};
}

std::string decode_probed_texture(const std::string& bytes, int width, int height, Texture& out) {
  int decoded_width = 0, decoded_height = 0, decoded_channels = 0;
  stbi_uc* pixels =
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                            &decoded_width, &decoded_height, &decoded_channels, 4);
  if (!pixels) return std::string("could not be decoded (") + stbi_failure_reason() + ")";
  const std::unique_ptr<stbi_uc, void (*)(void*)> owner(pixels, stbi_image_free);
  if (decoded_width != width || decoded_height != height) return "decoded to another size than its header says";
  out.width = width;
  out.height = height;
  out.has_alpha = decoded_channels == 2 || decoded_channels == 4;
  out.rgba.assign(pixels, pixels + texel_bytes(width, height));
  return {};
}

std::string decode_texture(const std::string& bytes, uint64_t byte_limit, Texture& out) {
  int width = 0, height = 0;
  std::string error = probe_texture(bytes, width, height);
  if (error.empty()) error = check_texture_size(width, height, byte_limit);
  if (error.empty()) error = decode_probed_texture(bytes, width, height, out);
  return error;
}

TextureFile read_texture_file(const std::string& path, uint64_t byte_limit) {
  TextureFile texture_file;
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  texture_file.opened = static_cast<bool>(file);
  if (!texture_file.opened) return texture_file;
  const std::streamoff size = file.tellg();
  texture_file.size = size < 0 ? std::numeric_limits<uint64_t>::max() : static_cast<uint64_t>(size);
  if (texture_file.size > byte_limit) return texture_file;
  texture_file.bytes.assign(static_cast<size_t>(size), '\0');
  file.seekg(0);
  texture_file.read = static_cast<bool>(file.read(texture_file.bytes.data(), size));
  return texture_file;
}

std::string texture_file_refusal(const TextureFile& file, uint64_t byte_limit) {
  if (!file.opened) return "cannot be opened";
  // Compressed images decode to more bytes than they store: a file larger than the budget is refused unread.
  if (file.size > byte_limit) {
    const uint64_t shown = file.size == std::numeric_limits<uint64_t>::max() ? 0 : file.size;
    return "a " + format_bytes(shown) + " file, more than the " + format_bytes(byte_limit) + " left for textures";
  }
  return file.read ? std::string() : std::string("cannot be read");
}

}  // namespace lueur
