// The A/B split view written by the CPU: the left side's columns from one film and the right side's from the
// other, each side's pixels exactly what a full render with its settings gives; a PNG also shows the divider.
#pragma once

#include <string>

#include "film/film.h"
#include "settings/settings.h"

namespace lueur {

/// `left`'s columns before `column`, `right`'s from it on (both the same size).
Image split_image(const Image& left, const Image& right, int column);

/// Writes the split view of `left` (rendered with `shown`) and `right` (rendered with compared_settings(shown)):
/// the image each side shows, and in an EXR every layer both films hold, split the same way. Throws IoError.
void write_split_image(const std::string& path, const Film& left, const Film& right, const Settings& shown,
                       const std::string& metadata);

}  // namespace lueur
