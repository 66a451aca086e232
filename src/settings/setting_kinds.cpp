// Text helpers and parsers shared by the setting rows.
#include "settings/setting_kinds.h"

#include <charconv>
#include <cmath>

namespace lueur::setting_rows {

std::string float_text(float v) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, v);
  return std::string(text, result.ptr);
}

std::optional<float> finite_float(const std::string& text) {
  size_t used = 0;
  float v = 0.0f;
  try {
    v = std::stof(text, &used);  // refuses a float that overflows or underflows
  } catch (const std::logic_error&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string number_text(double v) {
  // Whole bounds in full ("1048576", not the stream's "1.04858e+06", which names another number); others as the
  // shortest text that reads back ("0.5", "1e+30").
  if (std::abs(v) < 1e15 && v == std::floor(v)) return std::to_string(static_cast<long long>(v));
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, v);
  return std::string(text, result.ptr);
}

std::string in_quotes(const std::string& text) { return "'" + text + "'"; }

void append_listed(std::string& list, std::string_view item, char separator) {
  if (!list.empty()) list += separator;
  list += item;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

std::string json_key_of(std::string_view name) {
  std::string key(name);
  for (char& c : key)
    if (c == '-') c = '_';
  return key;
}

namespace {

template <typename T>
T parse_integer(const std::string& text, const SettingRange& range) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  const bool whole = !text.empty() && end == text.data() + text.size();
  if (whole && error == std::errc::result_out_of_range)
    throw ValueError(in_quotes(text) + " is outside " + range.text());
  if (!whole || error != std::errc())
    throw ValueError(in_quotes(text) + (std::is_signed_v<T> ? " is not an integer" : " is not a non-negative integer"));
  if (!range.contains(static_cast<double>(value))) throw ValueError(in_quotes(text) + " is outside " + range.text());
  return value;
}

}  // namespace

int64_t parse_signed(const std::string& text, const SettingRange& range) { return parse_integer<int64_t>(text, range); }

uint64_t parse_unsigned(const std::string& text, const SettingRange& range) {
  return parse_integer<uint64_t>(text, range);
}

float parse_real(const std::string& text, const SettingRange& range) {
  const std::optional<float> value = finite_float(text);
  if (!value) throw ValueError(in_quotes(text) + " is not a finite number");
  // The bounds as floats: "1e30" reads as the float nearest 1e30, which is above the double 1e30.
  const SettingRange bounds{static_cast<float>(range.min), static_cast<float>(range.max), range.min_open};
  if (!bounds.contains(*value)) throw ValueError(in_quotes(text) + " is outside " + range.text());
  return *value;
}

std::vector<float> parse_reals(const std::string& text, size_t count) {
  std::string cleaned = text;
  for (char& c : cleaned)
    if (c == ',') c = ' ';
  std::istringstream in(cleaned);
  std::vector<float> values;
  std::string token;
  while (in >> token) {
    const std::optional<float> v = finite_float(token);
    if (!v) throw ValueError(in_quotes(token) + " is not a finite number");
    values.push_back(*v);
  }
  if (values.size() != count)
    throw ValueError("expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()));
  return values;
}

std::string number_json_text(const nlohmann::json& value, const std::string& key) {
  if (!value.is_number()) throw ValueError(in_quotes(key) + " is not a number");
  return value.dump();
}

std::string string_json_text(const nlohmann::json& value, const std::string& key) {
  if (!value.is_string()) throw ValueError(in_quotes(key) + " is not a string");
  return value.get<std::string>();
}

double json_real(float v) { return std::stod(float_text(v)); }

Row base_row(std::string_view name, std::string value_name, std::string_view help, SettingEffect effect) {
  Row row;
  row.info.name = name;
  row.info.value_name = std::move(value_name);
  row.info.help = help;
  row.info.effect = effect;
  row.json_keys = {json_key_of(name)};
  return row;
}

void read_json_through_text(Row& row, JsonToText to_text) {
  row.read_json = [parse = row.parse, key = row.json_keys.front(), to_text](const nlohmann::json& root, Settings& s) {
    const auto it = root.find(key);
    if (it == root.end()) return;
    const std::string text = to_text(*it, key);
    try {
      parse(s, text);
    } catch (const ValueError& e) {
      throw ValueError(in_quotes(key) + ": " + e.what());
    }
  };
}

}  // namespace lueur::setting_rows
