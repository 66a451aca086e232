// The settings table's value checks as CLI11 validators, for lueur's and lueur-bench's own options (a header of its
// own so that the settings library itself never depends on CLI11). Depends on CLI11 and settings/setting_table.h.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "settings/setting_table.h"

namespace lueur {

/// A CLI11 check of an option by `error` (whole_number_error, finite_number_error, ...) within `range`: the same
/// words as the settings' own messages.
inline CLI::Validator checked_by(std::string (*error)(const std::string&, const SettingRange&), SettingRange range) {
  return CLI::Validator([error, range](std::string& text) { return error(text, range); }, "");
}

}  // namespace lueur
