// CLI11 checks for the programs' own numeric options (lueur's --threads and --checkpoint, lueur-bench's), in the
// words of the settings' messages ("'-1' is outside [0, 1024]", "'nan' is not a finite number"). CLI11's Range says
// "Value -1 not in range 0.000000 to 1000000000.000000", and lets NaN through (it compares).
#pragma once

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

#include "settings/setting_table.h"

namespace lueur {

/// The whole text a non-negative integer within `range`.
inline CLI::Validator whole_number_in(SettingRange range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool whole = !text.empty() && end == text.data() + text.size();
        if (!whole || (error != std::errc() && error != std::errc::result_out_of_range))
          return "'" + text + "' is not a non-negative integer";
        if (error == std::errc::result_out_of_range || !range.contains(static_cast<double>(value)))
          return "'" + text + "' is outside " + range.text();
        return {};
      },
      "");
}

/// The whole text one finite number within `range`.
inline CLI::Validator finite_number_in(SettingRange range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool whole = !text.empty() && end == text.data() + text.size();
        if (!whole || error != std::errc() || !std::isfinite(value)) return "'" + text + "' is not a finite number";
        if (!range.contains(value)) return "'" + text + "' is outside " + range.text();
        return {};
      },
      "");
}

}  // namespace lueur
