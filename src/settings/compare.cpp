// Comparable settings are read off the settings table, so a new estimator setting can be compared at once.
#include "settings/compare.h"

#include <array>

#include "settings/setting_table.h"

namespace lueur {

bool comparable(std::string_view name) {
  // The image's size and camera would put different pixels side by side; the comparison itself cannot nest.
  constexpr std::array<std::string_view, 5> kExcluded = {"size", "camera", "up", "start-view", "compare"};
  for (const std::string_view excluded : kExcluded)
    if (name == excluded) return false;
  for (const SettingInfo& info : setting_infos())
    if (info.name == name) return info.effect == SettingEffect::kRestart;
  return false;
}

std::vector<std::string_view> comparable_settings() {
  std::vector<std::string_view> names;
  for (const SettingInfo& info : setting_infos())
    if (comparable(info.name)) names.push_back(info.name);
  return names;
}

std::string comparable_list() {
  std::string list;
  for (const std::string_view name : comparable_settings()) {
    if (!list.empty()) list += '|';
    list += name;
  }
  return list;
}

std::optional<Settings> compared_settings(const Settings& settings) {
  if (settings.compare.empty()) return std::nullopt;
  const size_t equals = settings.compare.find('=');
  Settings right = settings;
  right.compare.clear();
  set_setting(right, settings.compare.substr(0, equals), settings.compare.substr(equals + 1));
  return right;
}

}  // namespace lueur
