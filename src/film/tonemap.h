// Display transform on the CPU: exposure, tone map, sRGB encoding. The GL display shader computes the same thing;
// this is its reference. Depends on core only.
#pragma once

#include "core/math.h"

#include <array>
#include <cstdint>
#include <string_view>

namespace lueur {

enum class ToneMap : int { kNone = 0, kReinhard = 1, kAces = 2 };
inline constexpr std::array<std::string_view, 3> kToneMapNames = {"none", "reinhard", "aces"};

struct DisplaySettings {
  float exposure = 0.0f;  ///< in stops: the linear image is scaled by 2^exposure
  ToneMap tonemap = ToneMap::kNone;
  bool operator==(const DisplaySettings&) const = default;
};

/// Krzysztof Narkowicz's fit of the ACES filmic curve.
inline float aces_fit(float x) {
  return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

inline float linear_to_srgb(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

/// Linear radiance to display value in [0, 1] before quantisation.
inline Vec3 display_transform(Vec3 c, const DisplaySettings& d) {
  c *= std::exp2(d.exposure);
  switch (d.tonemap) {
    case ToneMap::kNone: break;
    case ToneMap::kReinhard: c = c / (Vec3(1.0f) + c); break;
    case ToneMap::kAces: c = Vec3(aces_fit(c.r), aces_fit(c.g), aces_fit(c.b)); break;
  }
  return Vec3(linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b));
}

/// 8-bit quantisation with rounding; NaN maps to 0.
inline uint8_t quantize_unorm8(float v) {
  if (!(v > 0.0f)) return 0;
  return static_cast<uint8_t>(std::min(255.0f, v * 255.0f + 0.5f));
}

}  // namespace lueur
