// The A/B comparison: which settings a split view may change on its right side, and the settings that side renders
// with. Depends on the settings table.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "settings/settings.h"

namespace lueur {

/// Whether --compare may change this setting: one that changes the estimate (it restarts the accumulation) and
/// leaves the image's size, camera and scene alone, so that both sides show the same pixels of the same scene.
bool comparable(std::string_view name);
/// Those settings, in the table's order.
std::vector<std::string_view> comparable_settings();
/// The same as "a|b|c", for messages.
std::string comparable_list();

/// The settings the split's right side renders with: `settings` with the compared setting set (and no comparison);
/// nullopt when there is none.
std::optional<Settings> compared_settings(const Settings& settings);

/// The first column of the right side in an image `width` pixels wide.
inline int split_column(float split, int width) {
  const float column = split * static_cast<float>(width) + 0.5f;
  return column <= 0.0f ? 0 : column >= static_cast<float>(width) ? width : static_cast<int>(column);
}

}  // namespace lueur
