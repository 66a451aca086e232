// The settings table: every setting reads back what it writes, as command-line text and in view files; both accept
// exactly the same values; the settings written into images render the same image again; a change has the effect
// the table says; view files written before the table existed still load and render as before; the README names
// every setting.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "store/l1_cache.h"
#include "settings/setting_table.h"
#include "settings/view_file.h"
#include "test_support.h"

namespace lueur {
namespace {

/// Settings where every setting differs from its default.
Settings unusual_settings() {
  Settings s;
  s.camera = CameraSpec{Vec3(270.5f, 260.0f, -700.0f), Vec3(280.0f, 250.25f, 10.0f), Vec3(0.0f, 1.0f, 0.0f), 41.5f};
  s.up = Vec3(0.1f, 1.0f, 0.0f);
  s.render.width = 24;
  s.render.height = 18;
  s.render.enabled = {true, true, false, true, true};
  s.render.lights = LightStrategy::kPower;
  s.render.le_rays = 2;
  s.render.l1_rays = 3;
  s.render.blinn_k = 0.55f;
  s.render.l2_rays = 5;
  s.render.reuse = ReuseMode::kAverage;
  s.render.recompute_ratio = 0.3f;
  s.render.cache_cell_pixels = 3.5f;
  s.render.cache_mb = 96;
  s.render.reuse_diffuse_only = true;
  s.render.ao_rays = 2;
  s.render.ln_rays = 3;
  s.render.max_bounces = 5;
  s.render.ao_radius = 123.456f;
  s.render.seed = 18446744073709551557ull;  // beyond 2^53: must survive text and JSON exactly
  s.render.sampler = SamplerKind::kIndependent;
  s.weights = {0.5f, 0.25f, 2.0f, 1.5f};
  s.layer = Layer::kL1;
  s.display = {1.25f, ToneMap::kAces};
  s.smooth_normals = false;
  s.light_rig = false;
  s.render.camera_light = true;
  s.light_rig_scale = 0.5f;
  s.start_view = StartView::kOutside;
  s.accel = AccelKind::kEmbree;
  s.frames = 2;
  s.frame_limit = 100;
  s.time_limit = 600.5f;    // never reached by the renders below
  s.target_noise = 1e-20f;  // never reached by the renders below either
  s.watch = false;
  s.compare = "l1-rays=3";
  s.compare_split = 0.25f;
  return s;
}

/// Splits "--a 1 --b \"x y\"" as a shell would (double quotes only, as describe_settings writes them).
std::vector<std::string> shell_words(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  bool in_quotes = false, started = false;
  for (const char c : text) {
    if (c == '"') {
      in_quotes = !in_quotes;
      started = true;
    } else if (c == ' ' && !in_quotes) {
      if (started) words.push_back(word);
      word.clear();
      started = false;
    } else {
      word += c;
      started = true;
    }
  }
  if (started) words.push_back(word);
  return words;
}

TEST(SettingTable, EveryRowReadsBackItsOwnText) {
  const Settings unusual = unusual_settings();
  for (const SettingInfo& info : setting_infos()) {
    const std::optional<std::string> text = setting_text(unusual, info.name);
    ASSERT_TRUE(text.has_value()) << info.name;
    EXPECT_NE(*text, info.default_text) << info.name << " should differ from its default in this test";
    Settings read;
    set_setting(read, info.name, *text);
    EXPECT_EQ(setting_text(read, info.name), text) << info.name;
  }
}

TEST(SettingTable, TheDescriptionOfTheSettingsReadsBackTheSameSettings) {
  for (const Settings& original : {Settings{}, unusual_settings()}) {
    const std::vector<std::string> words = shell_words(describe_settings(original));
    Settings read;
    for (size_t i = 0; i < words.size(); ++i) {
      ASSERT_EQ(words[i].rfind("--", 0), 0u) << "not an option: " << words[i];
      const SettingInfo& info = setting_info(words[i].substr(2));
      set_setting(read, info.name, info.is_flag ? "true" : words.at(++i));
    }
    EXPECT_EQ(read, original) << describe_settings(original);
  }
}

TEST(SettingTable, ViewFilesRoundTripEverySetting) {
  const Settings unusual = unusual_settings();
  EXPECT_EQ(view_from_json(view_to_json(unusual)), unusual);
  EXPECT_EQ(view_from_json(view_to_json(Settings{})), Settings{});
}

/// Whether a value is accepted for a numeric setting on the command line and in a view file: the two must agree.
bool accepted(const SettingInfo& info, const std::string& text, bool& file_agrees) {
  bool on_command_line = true, in_file = true;
  try {
    Settings s;
    set_setting(s, info.name, text);
  } catch (const SettingError&) {
    on_command_line = false;
  }
  try {
    view_from_json("{\"lueur_view\": 1, \"" + info.json_key() + "\": " + text + "}");
  } catch (const ViewFileError&) {
    in_file = false;
  }
  file_agrees = on_command_line == in_file;
  return on_command_line;
}

TEST(SettingTable, CommandLineAndViewFilesAcceptTheSameRanges) {
  int checked = 0;
  for (const SettingInfo& info : setting_infos()) {
    if (!info.range || (info.value_name != "N" && info.value_name != "X")) continue;  // size and weights below
    const bool integer = info.value_name == "N";
    const auto text = [&](double v) -> std::string {
      if (integer && v >= 9e18) return "18446744073709551615";  // the largest uint64, beyond a long long
      std::ostringstream out;
      out.precision(17);
      if (integer)
        out << static_cast<long long>(v);
      else
        out << v;
      return out.str();
    };
    bool agrees = false;
    EXPECT_TRUE(accepted(info, text(info.range->max), agrees)) << info.name << " at its maximum";
    EXPECT_TRUE(agrees) << info.name;
    if (info.range->max < 9e18) {
      EXPECT_FALSE(accepted(info, text(info.range->max * 2 + 1), agrees)) << info.name << " beyond its maximum";
      EXPECT_TRUE(agrees) << info.name;
    }
    EXPECT_EQ(accepted(info, text(info.range->min), agrees), !info.range->min_open) << info.name << " at its minimum";
    EXPECT_TRUE(agrees) << info.name;
    // A view file saved before its first frame holds "frames": 0 and keeps the default: check below that.
    const double below = info.name == "frames" ? -1 : info.range->min - 1;
    EXPECT_FALSE(accepted(info, text(below), agrees)) << info.name << " below its minimum";
    EXPECT_TRUE(agrees) << info.name;
    if (info.slider) {
      EXPECT_GE(info.slider->min, info.range->min) << info.name << ": the panel's slider leaves the range";
      EXPECT_LE(info.slider->max, info.range->max) << info.name << ": the panel's slider leaves the range";
    }
    ++checked;
  }
  EXPECT_GE(checked, 10) << "rays, reals, seed and frame counts";
  Settings s;
  EXPECT_THROW(set_setting(s, "size", "16385x8"), SettingError);
  EXPECT_THROW(view_from_json("{\"lueur_view\": 1, \"width\": 16385}"), ViewFileError);
  EXPECT_THROW(set_setting(s, "weights", "l1=2e6"), SettingError);
  EXPECT_THROW(view_from_json("{\"lueur_view\": 1, \"weights\": {\"l1\": 2e6}}"), ViewFileError);
}

TEST(SettingTable, ErrorsNameTheSetting) {
  const auto command_line_error = [](const char* name, const char* text) {
    try {
      Settings s;
      set_setting(s, name, text);
    } catch (const SettingError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(command_line_error("l1-rays", "-3"), "--l1-rays: '-3' is outside [0, 4096]");
  EXPECT_EQ(command_line_error("seed", "-1"), "--seed: '-1' is not a non-negative integer");
  EXPECT_EQ(command_line_error("blinn-k", "nan"), "--blinn-k: 'nan' is not a finite number");
  EXPECT_EQ(command_line_error("lights", "sideways"),
            "--lights: 'sideways' is not one of all|uniform|area|power|importance");
  EXPECT_EQ(command_line_error("smooth-normals", "maybe"), "--smooth-normals: 'maybe' is not on|off");
  try {
    view_from_json("{\"lueur_view\": 1, \"l1_ray\": 3}");
    FAIL() << "a misspelt key was accepted";
  } catch (const ViewFileError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown setting 'l1_ray'"), std::string::npos) << e.what();
  }
}

TEST(SettingTable, AChangeHasTheEffectTheTableGivesIt) {
  const Settings base;
  const auto changed = [&](auto change) {
    Settings s = base;
    change(s);
    return change_effect(base, s);
  };
  EXPECT_EQ(change_effect(base, base), SettingEffect::kNone);
  EXPECT_EQ(changed([](Settings& s) { s.frames = 7; }), SettingEffect::kNone);
  EXPECT_EQ(changed([](Settings& s) { s.frame_limit = 7; }), SettingEffect::kNone);
  EXPECT_EQ(changed([](Settings& s) { s.weights[1] = 0.9f; }), SettingEffect::kDisplay);
  EXPECT_EQ(changed([](Settings& s) { s.display.exposure = 1.0f; }), SettingEffect::kDisplay);
  EXPECT_EQ(changed([](Settings& s) { s.layer = Layer::kAo; }), SettingEffect::kDisplay);
  EXPECT_EQ(changed([](Settings& s) { s.render.l1_rays = 1; }), SettingEffect::kRestart);
  EXPECT_EQ(changed([](Settings& s) { s.render.width = 100; }), SettingEffect::kRestart);
  EXPECT_EQ(changed([](Settings& s) { s.camera = CameraSpec{}; }), SettingEffect::kRestart);
  EXPECT_EQ(changed([](Settings& s) { s.up = Vec3(0, 0, 1); }), SettingEffect::kRestart);
  EXPECT_EQ(changed([](Settings& s) { s.smooth_normals = false; }), SettingEffect::kReload);
  EXPECT_EQ(changed([](Settings& s) { s.accel = AccelKind::kEmbree; }), SettingEffect::kReload);
  // The strongest effect wins.
  EXPECT_EQ(changed([](Settings& s) {
              s.weights[0] = 3.0f;
              s.render.seed = 4;
            }),
            SettingEffect::kRestart);
}

TEST(SettingTable, TheCommandLineHasAnOptionForEverySetting) {
  const test::CommandResult help = test::run_lueur("--help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  for (const SettingInfo& info : setting_infos())
    EXPECT_NE(help.output.find(info.option() + " "), std::string::npos) << info.option() << " is not in --help";
}

// Help that quotes a constant of the renderer quotes its value: --recompute-ratio's said the store modes fill with
// 16 shadow rays for sessions after the fill had become kL1CacheFillRays = 8.
TEST(SettingTable, RecomputeRatioHelpNamesTheStoresFillRays) {
  const std::string help(setting_info("recompute-ratio").help);
  EXPECT_NE(help.find("recompute with " + std::to_string(kL1CacheFillRays) + " shadow rays"), std::string::npos)
      << help;
}

// The options an image holds render that image again, byte for byte (the PNG holds them too, so its bytes match
// only if every setting was read back as written).
TEST(SettingTable, TheSettingsInAnImageRenderItAgain) {
  const std::string dir = test::make_temp_dir("settings-again");
  Settings s = unusual_settings();
  s.accel = AccelKind::kLueur;  // Embree may be missing from a build
  s.layer.reset();
  save_view_file(dir + "/view.json", s);
  const test::CommandResult from_file =
      test::run_lueur("--headless --view-file " + dir + "/view.json --out " + dir + "/from-file.png");
  ASSERT_EQ(from_file.exit_code, 0) << from_file.output;
  const test::CommandResult from_options =
      test::run_lueur("--headless " + describe_settings(s) + " --out " + dir + "/from-options.png");
  ASSERT_EQ(from_options.exit_code, 0) << from_options.output;
  EXPECT_EQ(test::read_file(dir + "/from-file.png"), test::read_file(dir + "/from-options.png"));
}

// A view saved by the window before the settings table existed (tests/views/): it loads with every value, and
// renders the image of the options it holds.
TEST(SettingTable, ViewFilesFromBeforeTheTableStillLoad) {
  const std::string path = std::string(LUEUR_SOURCE_DIR) + "/tests/views/before-the-settings-table.json";
  const Settings v = load_view_file(path);
  Settings expected;
  expected.camera = CameraSpec{Vec3(278, 273, -800), Vec3(278, 273, 0), Vec3(0, 1, 0), 39.3077f};
  expected.render.width = 40;
  expected.render.height = 30;
  expected.render.l1_rays = 3;
  expected.render.l2_rays = 2;
  expected.render.lights = LightStrategy::kUniform;
  expected.render.seed = 11;
  expected.weights = {1.0f, 0.8f, 0.3f, 1.0f, 1.0f};  // the file has no ln: its weight stays the default
  expected.display = {0.5f, ToneMap::kReinhard};
  expected.frames = 3;
  EXPECT_EQ(v, expected) << view_to_json(v);

  const std::string dir = test::make_temp_dir("old-view");
  const test::CommandResult from_file = test::run_lueur("--headless --view-file " + path + " --out " + dir + "/a.png");
  ASSERT_EQ(from_file.exit_code, 0) << from_file.output;
  const test::CommandResult from_options = test::run_lueur(
      "--headless --size 40x30 --frames 3 --l1-rays 3 --l2-rays 2 --lights uniform --seed 11 "
      "--weights le=1,l1=0.8,l2=0.3 --exposure 0.5 --tonemap reinhard --camera \"278 273 -800 278 273 0 39.3077\" "
      "--out " +
      dir + "/b.png");
  ASSERT_EQ(from_options.exit_code, 0) << from_options.output;
  EXPECT_EQ(test::read_file(dir + "/a.png"), test::read_file(dir + "/b.png"));
}

// The README's command line is the user's list of options: every setting of the table must be in it (a setting
// added without its documentation, or a README lost to a bad edit, fails here).
TEST(SettingTable, TheReadmesCommandLineNamesEverySetting) {
  std::ifstream file(std::string(LUEUR_SOURCE_DIR) + "/README.md");
  ASSERT_TRUE(file) << "no README.md in " << LUEUR_SOURCE_DIR;
  const std::string readme((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const size_t block = readme.find("## Command line");
  ASSERT_NE(block, std::string::npos) << "the README has no command-line section";
  const std::string section = readme.substr(block, readme.find("\n## ", block + 1) - block);
  for (const SettingInfo& info : setting_infos()) {
    const bool named = section.find("[" + info.option() + " ") != std::string::npos ||
                       section.find("[" + info.option() + "]") != std::string::npos;
    EXPECT_TRUE(named) << info.option() << " is not in the README's command line";
  }
}

}  // namespace
}  // namespace lueur
