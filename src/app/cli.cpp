// Command-line parsing with CLI11. The settings' options come from the settings table (one per row, with its help,
// value form and default); the program's own options (paths, headless, GL, threads) are added here. Every
// malformed value becomes a UsageError that names the option. An option given twice takes its last value.
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <optional>
#include <vector>

#include "accel/embree_backend.h"
#include "app/options.h"
#include "settings/cli_check.h"
#include "settings/setting_table.h"
#include "settings/view_file.h"

namespace lueur {
namespace {

bool ends_with_png(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

/// One option per row of the settings table; the text given is kept to be applied after any view file.
struct SettingOptions {
  std::vector<CLI::Option*> options;
  std::vector<std::string> texts;
};

void add_setting_options(CLI::App& app, SettingOptions& added) {
  const auto infos = setting_infos();
  added.texts.resize(infos.size());
  for (size_t i = 0; i < infos.size(); ++i) {
    const SettingInfo& info = infos[i];
    if (info.is_flag) {
      const std::string help(info.help);  // const: CLI11 takes a non-const string as the flag's result
      added.options.push_back(app.add_flag(info.option(), help));
      continue;
    }
    std::string help(info.help);
    if (!info.default_text.empty()) help += " (default " + info.default_text + ")";
    CLI::Option* option = app.add_option(info.option(), added.texts[i], help);
    option->type_name(info.value_name);
    added.options.push_back(option);
  }
}

/// The settings: the view file's, if one was given, then every setting option given, in the table's order.
Settings settings_from(const SettingOptions& given, const std::string& view_file) {
  Settings settings;
  if (!view_file.empty()) {
    try {
      settings = load_view_file(view_file, settings);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--view-file: ") + e.what());
    }
  }
  const auto infos = setting_infos();
  for (size_t i = 0; i < infos.size(); ++i) {
    if (given.options[i]->count() == 0) continue;
    try {
      set_setting(settings, infos[i].name, infos[i].is_flag ? "true" : given.texts[i]);
    } catch (const SettingError& e) {
      throw UsageError(e.what());
    }
  }
  return settings;
}

}  // namespace

std::optional<AppOptions> parse_command_line(int argc, char** argv, const ProgramName& program) {
  AppOptions o;
  CLI::App app{program.description, program.name};
  app.set_version_flag("--version", std::string(program.name) + " 0.1.0");
  // An option given twice takes its last value, as in most command-line tools (scripts/run.sh passes its own --out
  // before the user's).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::string gl;
  app.add_option("scene", o.scene_path, "OBJ scene (default: the embedded Cornell box with an apple)")
      ->type_name("FILE");
  app.add_flag("--headless", o.headless, "render to a file instead of opening a window");
  app.add_option("--out", o.out_path, "output image: .png (tone-mapped sRGB), .pfm (linear), .exr (linear, per pass)")
      ->type_name("FILE");
  SettingOptions settings;
  add_setting_options(app, settings);
  app.add_option("--threads", o.threads, "worker threads, at most 1024 (default 0: all cores)")
      ->type_name("N")
      ->check(checked_by(whole_number_error, {0, 1024}));
  app.add_option("--export-default-scene", o.export_default_scene,
                 "write the embedded default scene as OBJ + MTL to FILE.obj and exit")
      ->type_name("FILE");
  app.add_option("--export-scene", o.export_scene,
                 "write the scene as Lueur renders it (with the shading normals it computed and the light rig it "
                 "added) as OBJ + MTL to FILE.obj, print the view it opens with as a --camera option, and exit; "
                 "another renderer can then render what Lueur does")
      ->type_name("FILE");
  app.add_option("--gl", gl,
                 "headless PNG through the GL display shaders: egl|osmesa|auto (EGL, else OSMesa) or none (CPU, "
                 "default)")
      ->type_name("BACKEND");
  app.add_flag("--ui", o.ui, "draw the control panel into the headless screenshot (needs --gl)");
  app.add_option("--checkpoint", o.checkpoint_seconds,
                 "headless: every SECONDS, write the image so far and, beside it as OUT.lueur-state, what --resume "
                 "needs to go on (also at the end); 0: never")
      ->type_name("SECONDS")
      ->check(checked_by(finite_number_error, {0.0, 1e9}));
  app.add_option("--resume", o.resume_path,
                 "headless: go on from a state written by --checkpoint, with the same options (--frames may grow); "
                 "the final image is the one an uninterrupted render gives")
      ->type_name("FILE");
  app.add_option("--view-file", o.view_file,
                 "a view saved by the window (camera and all settings); options given as well override it")
      ->type_name("FILE");
  app.add_option("--state-file", o.state_file, "window: keep the current view and statistics in this JSON file")
      ->group("");  // for tests that drive the window

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return std::nullopt;
  } catch (const CLI::CallForVersion& e) {
    std::printf("%s\n", e.what());
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    if (const size_t nl = message.find('\n'); nl != std::string::npos) message.resize(nl);
    throw UsageError(message);
  }

  o.settings = settings_from(settings, o.view_file);
  if (o.settings.accel == AccelKind::kEmbree && !embree_available())
    throw UsageError("--accel embree: this build has no Embree (install libembree-dev and rebuild)");
  if (!gl.empty()) {
    const std::optional<HeadlessGl> kind = enum_from_name<HeadlessGl>(kHeadlessGlNames, gl);
    if (!kind) throw UsageError("--gl: '" + gl + "' is not one of none|egl|osmesa|auto");
    o.gl = *kind;
  }
  if (o.headless && o.gl != HeadlessGl::kNone && !o.out_path.empty() && !ends_with_png(o.out_path))
    throw UsageError("--gl " + gl + " takes a screenshot: --out must be a .png file");
  if (o.ui && o.gl == HeadlessGl::kNone && o.headless)
    throw UsageError("--ui draws the panel through GL: add --gl egl|osmesa|auto");
  if (!o.headless && (o.checkpoint_seconds > 0.0 || !o.resume_path.empty()))
    throw UsageError(std::string(o.resume_path.empty() ? "--checkpoint" : "--resume") + " needs --headless");
  if (o.headless && o.out_path.empty() && o.export_default_scene.empty() && o.export_scene.empty())
    throw UsageError("--headless needs --out FILE");
  return o;
}

std::string describe_options(const std::string& scene_path, const Settings& settings) {
  return "lueur " + (scene_path.empty() ? std::string() : "'" + scene_path + "' ") + describe_settings(settings);
}

}  // namespace lueur
