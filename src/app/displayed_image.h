// What the CPU writes for the image a user sees: the combined passes, a layer, or the noise view (whose false colours
// must not be exposed or tone mapped). The GL display makes the same choice in display/display_pipeline.cpp.
#pragma once

#include "film/film.h"
#include "film/noise_view.h"
#include "settings/settings.h"

namespace lueur {

inline Image displayed_image(const Film& film, const Settings& s) {
  return s.show_noise ? noise_view_image(film, s.render.enabled, s.weights, s.render.sampler)
                      : shown_image(film, s.render.enabled, s.weights, s.layer);
}

inline DisplaySettings displayed_transform(const Settings& s) { return s.show_noise ? DisplaySettings{} : s.display; }

}  // namespace lueur
