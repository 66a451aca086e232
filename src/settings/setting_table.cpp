// The public side of the settings table: names, text, descriptions and the effect of a change, all read off the
// rows in setting_rows.cpp.
#include "settings/setting_table.h"

#include <algorithm>

#include "settings/setting_kinds.h"

namespace lueur {
namespace {

using setting_rows::Row;

const Row& row_named(std::string_view name) {
  for (const Row& row : setting_rows::rows())
    if (row.info.name == name) return row;
  throw std::logic_error("no setting named '" + std::string(name) + "'");
}

/// What `parse` throws as a ValueError, or "" where it throws nothing.
template <typename Parse>
std::string value_error_of(Parse parse) {
  try {
    parse();
    return {};
  } catch (const setting_rows::ValueError& e) {
    return e.what();
  }
}

}  // namespace

std::string whole_number_error(const std::string& text, const SettingRange& range) {
  return value_error_of([&] { setting_rows::parse_unsigned(text, range); });
}

std::string finite_number_error(const std::string& text, const SettingRange& range) {
  return value_error_of([&] { setting_rows::parse_real(text, range); });
}

std::string SettingRange::text() const {
  std::string text(1, min_open ? '(' : '[');
  text += setting_rows::number_text(min);
  text += ", ";
  text += setting_rows::number_text(max);
  text += ']';
  return text;
}

std::string SettingInfo::json_key() const { return setting_rows::json_key_of(name); }

std::span<const SettingInfo> setting_infos() {
  static const std::vector<SettingInfo> infos = [] {
    std::vector<SettingInfo> all;
    for (const Row& row : setting_rows::rows()) all.push_back(row.info);
    return all;
  }();
  return infos;
}

const SettingInfo& setting_info(std::string_view name) {
  for (const SettingInfo& info : setting_infos())
    if (info.name == name) return info;
  throw std::logic_error("no setting named '" + std::string(name) + "'");
}

void set_setting(Settings& settings, std::string_view name, const std::string& text) {
  const Row& row = row_named(name);
  try {
    row.parse(settings, text);
  } catch (const setting_rows::ValueError& e) {
    throw SettingError(row.info.option() + ": " + e.what());
  }
}

std::optional<std::string> setting_text(const Settings& settings, std::string_view name) {
  return row_named(name).format(settings);
}

std::string describe_settings(const Settings& settings) {
  std::string text;
  for (const Row& row : setting_rows::rows()) {
    const std::optional<std::string> value = row.format(settings);
    if (!value || (!row.always_described && *value == row.info.default_text)) continue;
    setting_rows::append_listed(text, row.info.option(), ' ');
    if (row.info.is_flag) continue;  // set, since it differs from its default
    const bool quote = value->empty() || value->find(' ') != std::string::npos;
    text += " " + (quote ? "\"" + *value + "\"" : *value);
  }
  return text;
}

SettingEffect change_effect(const Settings& before, const Settings& after) {
  SettingEffect effect = SettingEffect::kNone;
  for (const Row& row : setting_rows::rows())
    if (!row.same(before, after)) effect = std::max(effect, row.info.effect);
  return effect;
}

}  // namespace lueur
