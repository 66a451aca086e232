// PNG through stb_image_write (plus our own tEXt chunk), PFM by hand, EXR through tinyexr; all written atomically.
#include "image/image_output.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cstring>

#include "core/atomic_file.h"

namespace lueur {
namespace {

std::string lowercase_extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

uint32_t crc32(const uint8_t* data, size_t size, uint32_t crc = 0) {
  crc = ~crc;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void append_be32(std::string& out, uint32_t v) {
  const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                         static_cast<char>(v)};
  out.append(bytes, 4);
}

/// A PNG tEXt chunk: keyword, NUL, Latin-1 text (we keep to ASCII).
std::string make_text_chunk(const std::string& keyword, const std::string& text) {
  std::string body = "tEXt" + keyword + '\0';
  for (const char c : text) body += (static_cast<unsigned char>(c) < 0x80 && c != '\0') ? c : '?';
  std::string chunk;
  append_be32(chunk, static_cast<uint32_t>(body.size() - 4));
  chunk += body;
  append_be32(chunk, crc32(reinterpret_cast<const uint8_t*>(body.data()), body.size()));
  return chunk;
}

void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<size_t>(size));
}

}  // namespace

std::vector<uint8_t> tonemap_to_rgb8(const Image& linear, const DisplaySettings& display) {
  std::vector<uint8_t> out(linear.rgb.size());
  for (size_t i = 0; i + 2 < linear.rgb.size(); i += 3) {
    const Vec3 d = display_transform(Vec3(linear.rgb[i], linear.rgb[i + 1], linear.rgb[i + 2]), display);
    out[i] = quantize_unorm8(d.r);
    out[i + 1] = quantize_unorm8(d.g);
    out[i + 2] = quantize_unorm8(d.b);
  }
  return out;
}

std::vector<NamedImage> film_layer_images(const Film& film) {
  std::vector<NamedImage> layers;
  for (int l = 0; l < kLayerCount; ++l)
    if (film.has(static_cast<Layer>(l)))
      layers.push_back({std::string(kLayerNames[static_cast<size_t>(l)]), layer_average(film, static_cast<Layer>(l))});
  return layers;
}

std::string encode_png(const Image& linear, const DisplaySettings& display, const std::string& metadata) {
  return encode_png_rgb8(tonemap_to_rgb8(linear, display), linear.width, linear.height, metadata);
}

std::string encode_png_rgb8(const std::vector<uint8_t>& pixels, int width, int height, const std::string& metadata) {
  if (pixels.size() != 3 * static_cast<size_t>(width) * static_cast<size_t>(height))
    throw IoError("PNG encoding failed: pixel buffer does not match the image size");
  std::string png;
  if (!stbi_write_png_to_func(append_to_string, &png, width, height, 3, pixels.data(), width * 3))
    throw IoError("PNG encoding failed");
  if (!metadata.empty()) {
    // Insert after the 8-byte signature and the 25-byte IHDR chunk, before the image data.
    constexpr size_t kAfterHeader = 8 + 25;
    png.insert(kAfterHeader, make_text_chunk("lueur", metadata));
  }
  return png;
}

std::string encode_pfm(const Image& linear) {
  std::string out = "PF\n" + std::to_string(linear.width) + " " + std::to_string(linear.height) + "\n-1.0\n";
  const size_t row = 3 * static_cast<size_t>(linear.width);
  for (int y = linear.height - 1; y >= 0; --y)
    out.append(reinterpret_cast<const char*>(linear.rgb.data() + static_cast<size_t>(y) * row), row * sizeof(float));
  return out;
}

Image decode_pfm(const std::string& bytes) {
  // Header: "PF", width, height, scale, each separated by one whitespace run; then the raster.
  size_t pos = 0;
  auto token = [&]() {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    const size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    return bytes.substr(start, pos - start);
  };
  Image image;
  if (token() != "PF") throw IoError("not a colour PFM");
  try {
    image.width = std::stoi(token());
    image.height = std::stoi(token());
    if (std::stof(token()) >= 0.0f) throw IoError("big-endian PFM not supported");
  } catch (const std::logic_error&) {
    throw IoError("malformed PFM header");
  }
  ++pos;  // the single whitespace byte after the scale
  const size_t row = 3 * static_cast<size_t>(image.width);
  if (image.width <= 0 || image.height <= 0 || bytes.size() - pos != row * static_cast<size_t>(image.height) * 4)
    throw IoError("PFM size does not match its header");
  image.rgb.resize(row * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    std::memcpy(image.rgb.data() + static_cast<size_t>(image.height - 1 - y) * row,
                bytes.data() + pos + static_cast<size_t>(y) * row * 4, row * 4);
  return image;
}

std::string encode_exr(const Image& combined, const std::vector<NamedImage>& layers, const std::string& metadata) {
  // Channel planes: the combined image as R, G, B, every layer as <name>.R/G/B. OpenEXR wants the channel list
  // sorted by name, so build (name, plane) pairs and sort them.
  const size_t pixels = static_cast<size_t>(combined.width) * static_cast<size_t>(combined.height);
  struct Channel {
    std::string name;
    std::vector<float> plane;
  };
  std::vector<Channel> channels;
  auto add_layer = [&](const std::string& prefix, const Image& image) {
    static constexpr const char* kComponents[3] = {"R", "G", "B"};
    for (size_t c = 0; c < 3; ++c) {
      Channel ch{prefix + kComponents[c], std::vector<float>(pixels)};
      for (size_t i = 0; i < pixels; ++i) ch.plane[i] = image.rgb[3 * i + c];
      channels.push_back(std::move(ch));
    }
  };
  add_layer("", combined);
  for (const NamedImage& layer : layers) add_layer(layer.name + ".", layer.image);
  std::sort(channels.begin(), channels.end(), [](const Channel& a, const Channel& b) { return a.name < b.name; });

  std::vector<EXRChannelInfo> infos(channels.size());
  std::vector<unsigned char*> planes(channels.size());
  std::vector<int> types(channels.size(), TINYEXR_PIXELTYPE_FLOAT);
  for (size_t i = 0; i < channels.size(); ++i) {
    std::memset(&infos[i], 0, sizeof(EXRChannelInfo));
    std::strncpy(infos[i].name, channels[i].name.c_str(), 255);
    infos[i].pixel_type = TINYEXR_PIXELTYPE_FLOAT;
    infos[i].x_sampling = infos[i].y_sampling = 1;
    planes[i] = reinterpret_cast<unsigned char*>(channels[i].plane.data());
  }

  EXRImage image;
  InitEXRImage(&image);
  image.images = planes.data();
  image.width = combined.width;
  image.height = combined.height;
  image.num_channels = static_cast<int>(channels.size());

  EXRHeader header;
  InitEXRHeader(&header);
  header.num_channels = static_cast<int>(channels.size());
  header.channels = infos.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = types.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

  EXRAttribute attribute;
  std::memset(&attribute, 0, sizeof attribute);
  std::string attribute_value = metadata;
  if (!metadata.empty()) {
    std::strncpy(attribute.name, "lueur", 255);
    std::strncpy(attribute.type, "string", 255);
    attribute.value = reinterpret_cast<unsigned char*>(attribute_value.data());
    attribute.size = static_cast<int>(attribute_value.size());
    header.num_custom_attributes = 1;
    header.custom_attributes = &attribute;
  }

  unsigned char* memory = nullptr;
  const char* error = nullptr;
  const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &error);
  if (size == 0) {
    const std::string why = error ? error : "unknown error";
    FreeEXRErrorMessage(error);
    throw IoError("EXR encoding failed: " + why);
  }
  std::string out(reinterpret_cast<const char*>(memory), size);
  std::free(memory);
  return out;
}

bool is_supported_image_path(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return ext == ".png" || ext == ".pfm" || ext == ".exr";
}

void write_image(const std::string& path, const Image& combined, const std::vector<NamedImage>& layers,
                 const DisplaySettings& display, const std::string& metadata) {
  const std::string ext = lowercase_extension(path);
  std::string bytes;
  if (ext == ".png")
    bytes = encode_png(combined, display, metadata);
  else if (ext == ".pfm")
    bytes = encode_pfm(combined);
  else if (ext == ".exr")
    bytes = encode_exr(combined, layers, metadata);
  else
    throw IoError("cannot write '" + path + "': unknown image format (use .png, .pfm or .exr)");
  write_file_atomically(path, bytes);
}

}  // namespace lueur
