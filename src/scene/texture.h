// Image textures of MTL materials: a diffuse colour map (map_Kd) and an alpha cutout mask (map_d), decoded once into
// 8-bit RGBA and sampled with bilinear filtering and repeat wrapping. Depends on core only (stb_image stays inside
// texture.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace lueur {

/// A decoded image, rows from the top, four bytes per texel (red, green, blue, alpha).
struct Texture {
  std::string name;  ///< the path as the MTL file wrote it, for messages
  int width = 0, height = 0;
  /// The file had an alpha channel: cutouts read it. A file without one (a grey mask) is read by its red channel.
  bool has_alpha = false;
  std::vector<uint8_t> rgba;

  uint64_t bytes() const { return rgba.size(); }
};

/// The linear albedo at texture coordinate `uv` (OBJ's convention: v = 0 at the bottom row): the four nearest texel
/// centres, decoded from sRGB and blended bilinearly, with the image repeated in both directions.
Vec3 sample_albedo(const Texture& texture, Vec2 uv);

/// The cutout mask's coverage at `uv`, in [0, 1], blended bilinearly like sample_albedo: alpha where the file has
/// it, red otherwise. Below 0.5 is a hole.
float sample_coverage(const Texture& texture, Vec2 uv);

/// Decodes the bytes of a PNG or JPEG (anything stb_image reads) into `out`, refusing images whose texels would take
/// more than `byte_limit` bytes before decoding them. Returns an empty string on success, otherwise why it failed.
/// It is probe_texture, check_texture_size and decode_probed_texture in turn (each returns why it failed, or "").
std::string decode_texture(const std::string& bytes, uint64_t byte_limit, Texture& out);

/// The image's size from its header alone.
std::string probe_texture(const std::string& bytes, int& width, int& height);
/// Refuses an image of no texels or whose texels need more than `byte_limit` bytes.
std::string check_texture_size(int width, int height, uint64_t byte_limit);
/// The bytes a decoded image of this size takes (Texture::bytes()).
uint64_t texel_bytes(int width, int height);
/// Decodes an image whose header probe_texture read, and which check_texture_size let through. Safe to call on
/// several threads at once.
std::string decode_probed_texture(const std::string& bytes, int width, int height, Texture& out);

/// A texture file as read_texture_file left it.
struct TextureFile {
  bool opened = false;
  uint64_t size = 0;  ///< the file's size in bytes (the largest value where it could not be told)
  bool read = false;  ///< `bytes` holds the whole file
  std::string bytes;
};

/// Opens the file at `path` and reads it, unless it is larger than `byte_limit`.
TextureFile read_texture_file(const std::string& path, uint64_t byte_limit);

/// Why `file` cannot be a texture when `byte_limit` bytes are left for textures ("cannot be opened", "a 5.0 MiB file,
/// more than the 1.0 MiB left for textures", "cannot be read"), in one line that the caller prefixes with the
/// file's name; "" when its bytes are there to decode.
std::string texture_file_refusal(const TextureFile& file, uint64_t byte_limit);

}  // namespace lueur
