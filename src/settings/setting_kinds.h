// The kinds of value a setting row is made of: integers, reals, names from a table and on/off switches, each read
// from command-line text and from a view file through the same parser; and the composite settings (size, passes,
// weights, the view, camera, up), made in composite_settings.cpp. Internal to settings/.
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "settings/setting_rows.h"

namespace lueur::setting_rows {

// ---- text ---------------------------------------------------------------------------------------------------------
std::string float_text(float v);                             ///< the shortest text that reads back as the same float
std::optional<float> finite_float(const std::string& text);  ///< the whole text as one finite float
std::string number_text(double v);                           ///< a bound in a message: "4096", "1e+30"
std::string in_quotes(const std::string& text);              ///< 'text'
std::vector<std::string> split(const std::string& text, char separator);
std::string json_key_of(std::string_view name);  ///< '-' becomes '_'
/// Appends `item` to a list, with `separator` before it unless the list is empty.
void append_listed(std::string& list, std::string_view item, char separator);

template <size_t N>
std::string names_list(const std::array<std::string_view, N>& names) {
  std::string list;
  for (const auto name : names) append_listed(list, name, '|');
  return list;
}

// ---- parsers (throw ValueError) -------------------------------------------------------------------------------------
int64_t parse_signed(const std::string& text, const SettingRange& range);
uint64_t parse_unsigned(const std::string& text, const SettingRange& range);
float parse_real(const std::string& text, const SettingRange& range);
std::vector<float> parse_reals(const std::string& text, size_t count);  ///< exactly `count`, spaces or commas between

/// A view-file number as the text the command line would have held, so that the same parser checks it.
std::string number_json_text(const nlohmann::json& value, const std::string& key);
/// A view-file string as command-line text.
std::string string_json_text(const nlohmann::json& value, const std::string& key);
/// A real as a JSON number that reads back as the same float and prints as its shortest text.
double json_real(float v);

// ---- rows -----------------------------------------------------------------------------------------------------------
/// A row's name, help and effect, with its view-file key.
Row base_row(std::string_view name, std::string value_name, std::string_view help, SettingEffect effect);

/// Reads the row's one key from a view file as text (`to_text` checks the JSON type) and parses it, naming the
/// key in any error.
using JsonToText = std::string (*)(const nlohmann::json& value, const std::string& key);
void read_json_through_text(Row& row, JsonToText to_text);

/// An integer member, signed or not; `get` returns it from a (const) Settings&.
template <typename Get>
Row integer_row(std::string_view name, std::string_view help, SettingEffect effect, Get get, SettingRange range,
                std::optional<SettingRange> slider = {}) {
  using T = std::remove_cvref_t<decltype(get(std::declval<Settings&>()))>;
  Row row = base_row(name, "N", help, effect);
  row.info.range = range;
  row.info.slider = slider;
  row.parse = [get, range](Settings& s, const std::string& text) {
    if constexpr (std::is_signed_v<T>)
      get(s) = static_cast<T>(parse_signed(text, range));
    else
      get(s) = static_cast<T>(parse_unsigned(text, range));
  };
  row.format = [get](const Settings& s) -> std::optional<std::string> { return std::to_string(get(s)); };
  row.write_json = [get, key = row.json_keys.front()](const Settings& s, nlohmann::json& root) { root[key] = get(s); };
  read_json_through_text(row, number_json_text);
  return row;
}

/// A float member.
template <typename Get>
Row real_row(std::string_view name, std::string_view help, SettingEffect effect, Get get, SettingRange range,
             std::optional<SettingRange> slider = {}) {
  Row row = base_row(name, "X", help, effect);
  row.info.range = range;
  row.info.slider = slider;
  row.parse = [get, range](Settings& s, const std::string& text) { get(s) = parse_real(text, range); };
  row.format = [get](const Settings& s) -> std::optional<std::string> { return float_text(get(s)); };
  row.write_json = [get, key = row.json_keys.front()](const Settings& s, nlohmann::json& root) {
    root[key] = json_real(get(s));
  };
  read_json_through_text(row, number_json_text);
  return row;
}

/// An enum member named by a name table.
template <typename Enum, size_t N, typename Get>
Row enum_row(std::string_view name, std::string_view help, SettingEffect effect,
             const std::array<std::string_view, N>& names, Get get) {
  Row row = base_row(name, names_list(names), help, effect);
  row.parse = [get, &names](Settings& s, const std::string& text) {
    const std::optional<Enum> value = enum_from_name<Enum>(names, text);
    if (!value) throw ValueError(in_quotes(text) + " is not one of " + names_list(names));
    get(s) = *value;
  };
  row.format = [get, &names](const Settings& s) -> std::optional<std::string> {
    return std::string(enum_name(names, get(s)));
  };
  row.write_json = [get, &names, key = row.json_keys.front()](const Settings& s, nlohmann::json& root) {
    root[key] = std::string(enum_name(names, get(s)));
  };
  read_json_through_text(row, string_json_text);
  return row;
}

/// A bool member: `on|off` on the command line, or a flag (present or absent); true or false in a view file.
template <typename Get>
Row switch_row(std::string_view name, std::string_view help, SettingEffect effect, Get get, bool is_flag) {
  const std::string on = is_flag ? "true" : "on", off = is_flag ? "false" : "off";
  Row row = base_row(name, is_flag ? "" : on + "|" + off, help, effect);
  row.info.is_flag = is_flag;
  row.always_described = !is_flag;  // a flag appears when it is set
  row.parse = [get, on, off](Settings& s, const std::string& text) {
    if (text != on && text != off) throw ValueError(in_quotes(text) + " is not " + on + "|" + off);
    get(s) = text == on;
  };
  row.format = [get, on, off](const Settings& s) -> std::optional<std::string> { return get(s) ? on : off; };
  row.write_json = [get, key = row.json_keys.front()](const Settings& s, nlohmann::json& root) { root[key] = get(s); };
  const auto parse = row.parse;
  const std::string key = row.json_keys.front();
  row.read_json = [parse, key, on, off](const nlohmann::json& root, Settings& s) {
    const auto it = root.find(key);
    if (it == root.end()) return;
    if (!it->is_boolean()) throw ValueError(in_quotes(key) + " is not true or false");
    parse(s, it->get<bool>() ? on : off);
  };
  return row;
}

// ---- the composite settings (composite_settings.cpp) ----------------------------------------------------------------
Row size_row();     ///< --size WxH; width and height in view files
Row passes_row();   ///< --passes le,l1; an array of names in view files
Row weights_row();  ///< --weights le=1,l1=0.6; an object in view files
Row view_row();     ///< --view combined|LAYER
Row camera_row();   ///< --camera "ex ey ez tx ty tz fovy"; an object with the up vector too in view files
Row compare_row();  ///< --compare SETTING=VALUE
Row up_row();       ///< --up "x y z"

}  // namespace lueur::setting_rows
