// The noise view: each pixel's estimated relative error (film/noise_estimate.h) in false colour on a log scale,
// with the scale and its labels drawn into the image's bottom edge, so that the window and every screenshot carry
// it. Depends on the noise estimate.
#pragma once

#include "film/film.h"
#include "film/noise_estimate.h"

namespace lueur {

/// The scale's ends: relative errors (the square root of a pixel's relMSE) of 0.1% and 100%.
inline constexpr float kNoiseViewLowest = 1e-3f, kNoiseViewHighest = 1.0f;

/// The scale's colour (sRGB, in [0, 1]) for a relative error; below and above the scale, its end colours.
Vec3 noise_scale_colour(float relative_error);

/// The noise view of the combined image as linear RGB, which the display's sRGB curve turns into the scale's
/// colours: show it with exposure 0 and no tone map. Black, with the scale, while the estimate is not known yet.
Image noise_view_image(const Film& film, const std::array<bool, kPassCount>& enabled,
                       const std::array<float, kPassCount>& weights, SamplerKind sampler);

}  // namespace lueur
