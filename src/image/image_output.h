// Writing images: PNG (tone-mapped 8-bit sRGB), PFM (linear float RGB) and EXR (linear, one layer per pass).
// Every file is written to a temporary file and renamed. Depends on the film (its sums, tone map); no GL.
#pragma once

#include <string>
#include <vector>

#include "film/film.h"
#include "film/tonemap.h"

namespace lueur {

/// A named linear layer for the EXR writer, e.g. {"l1", image}.
struct NamedImage {
  std::string name;
  Image image;
};

/// The average of every layer the film holds, named as in kLayerNames: the EXR's layers.
std::vector<NamedImage> film_layer_images(const Film& film);

/// Encodes a tone-mapped 8-bit RGB PNG; `metadata` goes into a tEXt chunk with the key "lueur" when not empty.
std::string encode_png(const Image& linear, const DisplaySettings& display, const std::string& metadata = {});
/// Encodes already tone-mapped 8-bit RGB pixels (rows top to bottom), e.g. read back from the GL display.
std::string encode_png_rgb8(const std::vector<uint8_t>& pixels, int width, int height,
                            const std::string& metadata = {});
/// Encodes a Portable Float Map (little-endian, bottom row first as the format requires).
std::string encode_pfm(const Image& linear);
/// Encodes a single-part EXR: the combined image as R, G, B and each layer as <name>.R, <name>.G, <name>.B (float).
/// `metadata` is stored as a string header attribute "lueur".
std::string encode_exr(const Image& combined, const std::vector<NamedImage>& layers, const std::string& metadata = {});

/// Picks the format from the extension (.png, .pfm, .exr) and writes atomically. Throws IoError.
void write_image(const std::string& path, const Image& combined, const std::vector<NamedImage>& layers,
                 const DisplaySettings& display, const std::string& metadata = {});

/// True when the extension is one write_image knows.
bool is_supported_image_path(const std::string& path);

/// The 8-bit sRGB pixels the PNG would hold (rows top to bottom, RGB).
std::vector<uint8_t> tonemap_to_rgb8(const Image& linear, const DisplaySettings& display);

/// Reads a PFM written by encode_pfm (for tests and tools). Throws IoError on a malformed file.
Image decode_pfm(const std::string& bytes);

}  // namespace lueur
