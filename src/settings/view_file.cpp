// JSON form of the settings, made from the rows of the settings table.
#include "settings/view_file.h"

#include <algorithm>

#include "core/atomic_file.h"
#include "core/regular_file.h"
#include "settings/setting_rows.h"

namespace lueur {

using nlohmann::json;

namespace {

bool is_setting_key(const std::string& key) {
  if (key == "lueur_view") return true;
  for (const setting_rows::Row& row : setting_rows::rows())
    if (std::find(row.json_keys.begin(), row.json_keys.end(), key) != row.json_keys.end()) return true;
  return false;
}

}  // namespace

std::string view_to_json(const Settings& settings) {
  json root = {{"lueur_view", 1}};
  for (const setting_rows::Row& row : setting_rows::rows()) row.write_json(settings, root);
  return root.dump(2) + "\n";
}

Settings view_from_json(const std::string& text, const Settings& defaults) {
  const json root = json::parse(text, nullptr, false);
  if (root.is_discarded()) throw ViewFileError("view file: not valid JSON");
  if (!root.is_object() || !root.contains("lueur_view"))
    throw ViewFileError("view file: not a Lueur view (no 'lueur_view')");
  for (const auto& item : root.items())
    if (!is_setting_key(item.key())) throw ViewFileError("view file: unknown setting '" + item.key() + "'");
  Settings settings = defaults;
  for (const setting_rows::Row& row : setting_rows::rows()) {
    try {
      row.read_json(root, settings);
    } catch (const setting_rows::ValueError& e) {
      throw ViewFileError(std::string("view file: ") + e.what());
    }
  }
  return settings;
}

void save_view_file(const std::string& path, const Settings& settings) {
  write_file_atomically(path, view_to_json(settings));
}

Settings load_view_file(const std::string& path, const Settings& defaults) {
  // A view is a few kilobytes of JSON; the cap keeps /dev/zero or a huge file named by mistake from filling memory.
  constexpr uint64_t kMaxViewFileBytes = uint64_t{16} << 20;
  std::string text;
  try {
    text = read_regular_file(path, kMaxViewFileBytes);
  } catch (const FileReadError& e) {
    throw IoError(e.what());
  }
  try {
    return view_from_json(text, defaults);
  } catch (const ViewFileError& e) {
    throw ViewFileError(path + ": " + e.what());
  }
}

}  // namespace lueur
