// The rows behind settings/setting_table.h: how each setting is read from and written to command-line text and
// view files. Internal to settings/ (the only place that sees the JSON library's types).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "settings/setting_table.h"

namespace lueur::setting_rows {

/// What is wrong with a value, without the setting's name ("'-3' is outside [0, 4096]"): the caller adds where
/// the value came from.
struct ValueError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Row {
  SettingInfo info;
  /// Sets the value from its command-line text; throws ValueError.
  std::function<void(Settings&, const std::string& text)> parse;
  /// The command-line text; nullopt when the setting is unset.
  std::function<std::optional<std::string>(const Settings&)> format;
  /// Whether two settings hold the same value; by default, whether their texts are equal.
  std::function<bool(const Settings&, const Settings&)> same;
  /// The view-file keys the row reads and writes (by default the name with '_' for '-').
  std::vector<std::string> json_keys;
  /// Writes the value into a view file's root object (nothing when unset).
  std::function<void(const Settings&, nlohmann::json& root)> write_json;
  /// Reads the value from a view file's root object, when it is there; throws ValueError naming the key.
  std::function<void(const nlohmann::json& root, Settings&)> read_json;
  /// Whether describe_settings writes the option even when its text is the default one.
  bool always_described = true;
};

/// Every row, in the table's order.
const std::vector<Row>& rows();

}  // namespace lueur::setting_rows
