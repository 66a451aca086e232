// The table of settings: one row per setting of the model in settings/settings.h, with its name, range, default,
// help and what a change to it does. The command line, view files, the settings written into images and the
// panel's limits are all made from it, so a new setting is one row (setting_rows.cpp) plus, where it has one, its
// widget. Depends on settings/settings.h; no JSON, CLI or UI library in this header.
#pragma once

#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "settings/settings.h"

namespace lueur {

/// What a change to a setting does, weakest first: the strongest among the settings that changed wins.
enum class SettingEffect : int {
  kNone = 0,     ///< frame counts: neither the estimate nor the picture changes
  kDisplay = 1,  ///< applied when the image is shown (weights, exposure, tone map, layer): no restart
  kRestart = 2,  ///< changes the estimate: the accumulation restarts
  kReload = 3,   ///< changes the traced scene (normals, back-end): the scene is prepared again, then restarts
};

/// A closed numeric interval; `min_open` excludes `min` itself.
struct SettingRange {
  double min = 0.0, max = 0.0;
  bool min_open = false;
  bool contains(double v) const { return v <= max && (min_open ? v > min : v >= min); }
  std::string text() const;  ///< e.g. "[0, 4096]" or "(0, 1e+30]"
};

/// What the rest of Lueur reads about a setting.
struct SettingInfo {
  std::string_view name;   ///< "l1-rays": the option --l1-rays and the view-file key l1_rays
  std::string value_name;  ///< how the value is written on the command line: "N", "WxH", "area|uniform"...
  std::string_view help;
  SettingEffect effect = SettingEffect::kRestart;
  std::optional<SettingRange> range;   ///< numbers: the values accepted anywhere
  std::optional<SettingRange> slider;  ///< numbers: the panel slider's span (within `range`)
  bool is_flag = false;                ///< on the command line, present or absent (--reuse-diffuse-only)
  std::string default_text;            ///< the value in a default-constructed Settings, as text
  std::string option() const { return "--" + std::string(name); }
  std::string json_key() const;  ///< the name with '-' as '_'
};

/// A value that a setting cannot take; the message names the setting as the source had it ("--l1-rays: ..." on the
/// command line, "view file: 'l1_rays' ..." in a view file).
struct SettingError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Every setting, in the order of the command line's help and of the settings written into images.
std::span<const SettingInfo> setting_infos();
/// The row named `name`; a name that is not in the table is a programming error (std::logic_error).
const SettingInfo& setting_info(std::string_view name);

/// Sets one setting from its command-line text (a flag takes "true" or "false"). Throws SettingError.
void set_setting(Settings& settings, std::string_view name, const std::string& text);
/// The setting's command-line text; nullopt when it is unset (no camera given, the combined view...).
std::optional<std::string> setting_text(const Settings& settings, std::string_view name);

/// The settings as command-line options ("--size 512x512 --frames 64 ..."), stored in every saved image so that
/// it can be rendered again. Optional settings appear only when they are set or differ from their default.
std::string describe_settings(const Settings& settings);

/// The strongest effect among the settings that differ between `before` and `after` (kNone when none does).
SettingEffect change_effect(const Settings& before, const Settings& after);

/// What is wrong with the text of one of a program's own options (lueur's --threads, lueur-bench's seconds), in the
/// settings' words: "'1.5' is not a non-negative integer", "'nan' is not a finite number", "'-1' is outside [0, 9]";
/// empty where nothing is. (CLI11's Range let NaN through and wrote its bounds as 1000000000.000000.)
std::string whole_number_error(const std::string& text, const SettingRange& range);
std::string finite_number_error(const std::string& text, const SettingRange& range);

}  // namespace lueur
