// False colour, the scale bar and its labels, in a 3 x 5 pixel font drawn here.
#include "film/noise_view.h"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace lueur {
namespace {

/// The scale's colours, dark blue (quiet) to red (noisy), evenly spaced in log error.
constexpr std::array<Vec3, 5> kScaleStops = {Vec3(0.05f, 0.03f, 0.25f), Vec3(0.10f, 0.35f, 0.85f),
                                             Vec3(0.10f, 0.75f, 0.55f), Vec3(0.95f, 0.80f, 0.15f),
                                             Vec3(0.85f, 0.10f, 0.10f)};

/// Where a relative error sits on the scale, 0 at its lowest end and 1 at its highest.
float scale_position(float relative_error) {
  const float lowest = std::log10(kNoiseViewLowest), highest = std::log10(kNoiseViewHighest);
  const float e = std::max(relative_error, kNoiseViewLowest);
  return std::clamp((std::log10(e) - lowest) / (highest - lowest), 0.0f, 1.0f);
}

Vec3 colour_at(float position) {
  const float x = position * static_cast<float>(kScaleStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(x), kScaleStops.size() - 2);
  const float t = x - static_cast<float>(i);
  return kScaleStops[i] * (1.0f - t) + kScaleStops[i + 1] * t;
}

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

/// Glyphs three pixels wide and five high, a row of three bits per line, top line first.
uint16_t glyph(char c) {
  switch (c) {
    case '0':
      return 0b111'101'101'101'111;
    case '1':
      return 0b010'110'010'010'111;
    case '2':
      return 0b111'001'111'100'111;
    case '3':
      return 0b111'001'111'001'111;
    case '4':
      return 0b101'101'111'001'001;
    case '5':
      return 0b111'100'111'001'111;
    case '6':
      return 0b111'100'111'101'111;
    case '7':
      return 0b111'001'001'001'001;
    case '8':
      return 0b111'101'111'101'111;
    case '9':
      return 0b111'101'111'001'111;
    case '.':
      return 0b000'000'000'000'010;
    case '%':
      return 0b101'001'010'100'101;
    default:
      return 0;
  }
}

struct Canvas {
  Image& image;
  void set(int x, int y, const Vec3& linear) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x));
    image.rgb[i] = linear.r;
    image.rgb[i + 1] = linear.g;
    image.rgb[i + 2] = linear.b;
  }
  void fill(int x0, int y0, int x1, int y1, const Vec3& linear) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, linear);
  }
  /// `text` with its left edge at x and top at y, each font pixel `scale` pixels wide.
  void text(std::string_view text, int x, int y, int scale, const Vec3& linear) {
    for (const char c : text) {
      const uint16_t bits = glyph(c);
      for (int row = 0; row < 5; ++row)
        for (int column = 0; column < 3; ++column)
          if (bits & (1u << (14 - (row * 3 + column))))
            fill(x + column * scale, y + row * scale, x + (column + 1) * scale, y + (row + 1) * scale, linear);
      x += 4 * scale;
    }
  }
};

int text_width(std::string_view text, int scale) { return static_cast<int>(text.size()) * 4 * scale - scale; }

Vec3 linear_of(const Vec3& srgb) {
  return Vec3(srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b));
}

/// The scale along the bottom edge: a dark strip holding the colour bar and, above it, its decade labels.
void draw_scale(Image& image) {
  if (image.width < 48 || image.height < 32) return;  // too small to read: the colours alone
  Canvas canvas{image};
  const int scale = std::max(1, image.height / 160);
  const int margin = 2 * scale, bar_height = 4 * scale, label_height = 5 * scale;
  const int strip_height = margin + label_height + scale + bar_height + margin;
  const int top = image.height - strip_height;
  canvas.fill(0, top, image.width, image.height, Vec3(0.0f));
  const int bar_left = margin + 3 * scale, bar_right = image.width - margin - 8 * scale;
  const int bar_top = top + margin + label_height + scale;
  for (int x = bar_left; x < bar_right; ++x) {
    const float position = static_cast<float>(x - bar_left) / static_cast<float>(std::max(bar_right - bar_left - 1, 1));
    canvas.fill(x, bar_top, x + 1, bar_top + bar_height, linear_of(colour_at(position)));
  }
  constexpr std::array<std::string_view, 4> kLabels = {"0.1%", "1%", "10%", "100%"};
  for (size_t k = 0; k < kLabels.size(); ++k) {
    const float position = static_cast<float>(k) / static_cast<float>(kLabels.size() - 1);
    const int centre = bar_left + static_cast<int>(position * static_cast<float>(bar_right - bar_left - 1));
    const int width = text_width(kLabels[k], scale);
    const int left = std::clamp(centre - width / 2, margin, image.width - margin - width);
    canvas.text(kLabels[k], left, top + margin, scale, Vec3(1.0f));
  }
}

}  // namespace

Vec3 noise_scale_colour(float relative_error) { return colour_at(scale_position(relative_error)); }

Image noise_view_image(const Film& film, const std::array<bool, kPassCount>& enabled,
                       const std::array<float, kPassCount>& weights, SamplerKind sampler) {
  Image view{film.width, film.height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  const Image errors = pixel_noise_map(film, enabled, weights, sampler);
  // The scale in 1024 linear colours: a pixel's colour is a look-up, not three powers.
  static const std::array<Vec3, 1024> kLinearScale = [] {
    std::array<Vec3, 1024> table;
    for (size_t k = 0; k < table.size(); ++k)
      table[k] = linear_of(colour_at(static_cast<float>(k) / static_cast<float>(table.size() - 1)));
    return table;
  }();
  if (!errors.rgb.empty())
    for (size_t i = 0; i < film.pixel_count(); ++i) {
      const float position = scale_position(errors.rgb[3 * i]);
      const Vec3 c = kLinearScale[static_cast<size_t>(position * static_cast<float>(kLinearScale.size() - 1) + 0.5f)];
      view.rgb[3 * i] = c.r;
      view.rgb[3 * i + 1] = c.g;
      view.rgb[3 * i + 2] = c.b;
    }
  draw_scale(view);
  return view;
}

}  // namespace lueur
