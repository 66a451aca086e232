// Command-line parsing with CLI11. Every malformed value becomes a UsageError that names the option.
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <optional>
#include <sstream>
#include <type_traits>
#include <vector>

#include "accel/embree_backend.h"
#include "app/options.h"

namespace lueur {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

/// The number `text` holds, if it is one finite float or double and nothing else (std::stof / std::stod, so that a
/// float that overflows or underflows is refused, as before).
template <typename Real>
std::optional<Real> parse_finite(const std::string& text) {
  size_t used = 0;
  Real v{};
  try {
    if constexpr (std::is_same_v<Real, float>)
      v = std::stof(text, &used);
    else
      v = std::stod(text, &used);
  } catch (const std::logic_error&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Reads exactly `count` finite floats separated by spaces or commas.
std::vector<float> parse_floats(const std::string& option, const std::string& text, size_t count) {
  std::string cleaned = text;
  for (char& c : cleaned)
    if (c == ',') c = ' ';
  std::istringstream in(cleaned);
  std::vector<float> values;
  std::string token;
  while (in >> token) {
    const std::optional<float> v = parse_finite<float>(token);
    if (!v) throw UsageError(option + ": '" + token + "' is not a finite number");
    values.push_back(*v);
  }
  if (values.size() != count)
    throw UsageError(option + ": expected " + std::to_string(count) + " numbers, got " + std::to_string(values.size()));
  return values;
}

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

/// A finite real number in [lo, hi] (in (0, hi] when `exclusive_lo`). CLI11's Range lets NaN through, since every
/// comparison with it is false, and prints an infinite bound as its 300 digits.
CLI::Validator finite_in(double lo, double hi, bool exclusive_lo = false) {
  const std::string range = (exclusive_lo ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + "]";
  return CLI::Validator(
      [lo, hi, exclusive_lo, range](std::string& text) -> std::string {
        const std::optional<double> v = parse_finite<double>(text);
        if (!v) return "'" + text + "' is not a finite number";
        if (*v < lo || *v > hi || (exclusive_lo && *v == lo)) return "'" + text + "' is outside " + range;
        return {};
      },
      "NUMBER in " + range);
}

/// A non-negative decimal integer (CLI11 wraps "-1" into an unsigned option's largest value).
const CLI::Validator kNonNegativeInteger(
    [](std::string& text) -> std::string {
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
        return "'" + text + "' is not a non-negative integer";
      return {};
    },
    "INTEGER >= 0");

template <typename Enum, size_t N>
Enum parse_enum(const std::string& option, const std::array<std::string_view, N>& names, const std::string& text) {
  if (const auto value = enum_from_name<Enum>(names, text)) return *value;
  std::string allowed;
  for (const auto name : names) {
    if (!allowed.empty()) allowed += '|';
    allowed += name;
  }
  throw UsageError(option + ": '" + text + "' is not one of " + allowed);
}

void parse_size(const std::string& text, RenderSettings& render) {
  const size_t x = text.find_first_of("xX");
  int w = 0, h = 0;
  try {
    size_t used_w = 0, used_h = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    w = std::stoi(text.substr(0, x), &used_w);
    h = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::logic_error&) {
    throw UsageError("--size: '" + text + "' is not WIDTHxHEIGHT");
  }
  if (w < 1 || h < 1 || w > 16384 || h > 16384) throw UsageError("--size: " + text + " is outside 1x1 .. 16384x16384");
  render.width = w;
  render.height = h;
}

void parse_passes(const std::string& text, RenderSettings& render) {
  render.enabled.fill(false);
  for (const std::string& name : split(text, ',')) {
    const Pass pass = parse_enum<Pass>("--passes", kPassNames, name);
    render.enabled[static_cast<size_t>(pass)] = true;
  }
}

void parse_weights(const std::string& text, std::array<float, kPassCount>& weights) {
  for (const std::string& item : split(text, ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos) throw UsageError("--weights: '" + item + "' is not PASS=WEIGHT");
    const Pass pass = parse_enum<Pass>("--weights", kPassNames, item.substr(0, eq));
    weights[static_cast<size_t>(pass)] = parse_floats("--weights", item.substr(eq + 1), 1)[0];
  }
}

bool ends_with_png(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png";
}

/// Applies a saved view, then puts back every value an option set directly: options given override the file.
void apply_view_file(const CLI::App& app, AppOptions& o) {
  const AppOptions given = o;
  ViewState view;
  try {
    view = load_view_file(o.view_file, view_from_options(o));
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--view-file: ") + e.what());
  }
  apply_view(view, o);
  const auto keep = [&](const char* option, auto member) {
    if (app.count(option) > 0) o.*member = given.*member;
  };
  const auto keep_render = [&](const char* option, auto member) {
    if (app.count(option) > 0) o.render.*member = given.render.*member;
  };
  keep("--frames", &AppOptions::frames);
  keep("--frame-limit", &AppOptions::frame_limit);
  keep_render("--l1-rays", &RenderSettings::l1_rays);
  keep_render("--blinn-k", &RenderSettings::blinn_k);
  keep_render("--l2-rays", &RenderSettings::l2_rays);
  keep_render("--recompute-ratio", &RenderSettings::recompute_ratio);
  keep_render("--reuse-diffuse-only", &RenderSettings::reuse_diffuse_only);
  keep_render("--ao-rays", &RenderSettings::ao_rays);
  keep_render("--ao-radius", &RenderSettings::ao_radius);
  keep_render("--seed", &RenderSettings::seed);
  if (app.count("--exposure") > 0) o.display.exposure = given.display.exposure;
}

}  // namespace

std::optional<AppOptions> parse_command_line(int argc, char** argv) {
  AppOptions o;
  CLI::App app{"Lueur: a progressive CPU ray tracer of direct (L1) and one-bounce indirect (L2) light", "lueur"};
  app.set_version_flag("--version", "lueur 0.1.0");
  // An option given twice takes its last value, as in most command-line tools (scripts/run.sh passes its own --out
  // before the user's).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  std::string size, camera, up, passes, weights, lights, smooth, tonemap, reuse, view, gl, accel;
  app.add_option("scene", o.scene_path, "OBJ scene (default: the embedded Cornell box with an apple)");
  app.add_flag("--headless", o.headless, "render to a file instead of opening a window");
  app.add_option("--out", o.out_path, "output image: .png (tone-mapped sRGB), .pfm (linear), .exr (linear, per pass)");
  app.add_option("--frames", o.frames, "frames to accumulate (default 64)")->check(CLI::Range(1, 1000000));
  app.add_option("--size", size, "image size WIDTHxHEIGHT (default 512x512)");
  app.add_option("--camera", camera, "\"ex ey ez tx ty tz fovy_degrees\"");
  app.add_option("--up", up, "\"x y z\" camera up vector (default 0 1 0)");
  app.add_option("--passes", passes, "comma-separated passes: le,l1,l2,ao (default le,l1,l2)");
  app.add_option("--weights", weights, "pass weights, e.g. le=1,l1=0.6");
  app.add_option("--lights", lights, "light sampling: all|uniform|area|power (default area)");
  app.add_option("--l1-rays", o.render.l1_rays, "shadow rays per pixel per frame (default 16)")
      ->check(CLI::Range(0, 4096));
  app.add_option("--blinn-k", o.render.blinn_k, "Lambert share K of the Blinn-Phong mix (default 0.7)")
      ->check(finite_in(0.0, 1.0));
  app.add_option("--l2-rays", o.render.l2_rays, "L2 bounce rays per pixel per frame (default 16)")
      ->check(CLI::Range(0, 4096));
  app.add_option("--reuse", reuse, "L1 reuse for L2: off|frame|average (default frame)");
  app.add_option("--recompute-ratio", o.render.recompute_ratio,
                 "share of the L1 rays used to recompute L1 where it cannot be reused (default 0.125)")
      ->check(finite_in(0.0, 16.0));
  app.add_flag("--reuse-diffuse-only", o.render.reuse_diffuse_only,
               "reuse only the view-independent part of L1 (no bias on glossy surfaces)");
  app.add_option("--ao-rays", o.render.ao_rays, "AO rays per pixel per frame (default 16)")->check(CLI::Range(0, 4096));
  app.add_option("--ao-radius", o.render.ao_radius, "AO radius in world units (default: scene diagonal / 10)")
      ->check(finite_in(0.0, 1e30, true));
  app.add_option("--view", view,
                 "what the PNG/PFM shows: combined (default), a pass (le|l1|l2|ao) or l2-reused|l2-recomputed|"
                 "reuse-fraction|l1-diffuse");
  app.add_option("--smooth-normals", smooth, "on|off: compute smooth normals for files without them (default on)");
  app.add_option("--seed", o.render.seed, "random seed (default 0)")->check(kNonNegativeInteger);
  app.add_option("--accel", accel, "acceleration structure: lueur|embree (default lueur)");
  app.add_option("--threads", o.threads, "worker threads (default: all cores)")->check(CLI::Range(0, 1024));
  app.add_option("--exposure", o.display.exposure, "exposure in stops (default 0)")->check(finite_in(-30.0, 30.0));
  app.add_option("--tonemap", tonemap, "none|reinhard|aces (default none)");
  app.add_option("--export-default-scene", o.export_default_scene,
                 "write the embedded default scene as OBJ + MTL to FILE.obj and exit");
  app.add_option("--gl", gl,
                 "headless PNG through the GL display shaders: egl|osmesa|auto (EGL, else OSMesa) or none (CPU, "
                 "default)");
  app.add_flag("--ui", o.ui, "draw the control panel into the headless screenshot (needs --gl)");
  app.add_option("--view-file", o.view_file,
                 "a view saved by the window (camera and all settings); options given as well override it");
  app.add_option("--frame-limit", o.frame_limit, "window: stop accumulating after this many frames (0: never)")
      ->check(kNonNegativeInteger);
  app.add_option("--state-file", o.state_file, "window: keep the current view and statistics in this JSON file")
      ->group("");  // for tests that drive the window

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return std::nullopt;
  } catch (const CLI::CallForVersion&) {
    std::printf("lueur 0.1.0\n");
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string message = e.what();
    if (const size_t nl = message.find('\n'); nl != std::string::npos) message.resize(nl);
    throw UsageError(message);
  }

  if (!o.view_file.empty()) apply_view_file(app, o);
  if (!size.empty()) parse_size(size, o.render);
  if (!passes.empty()) parse_passes(passes, o.render);
  if (!weights.empty()) parse_weights(weights, o.weights);
  if (!lights.empty()) o.render.lights = parse_enum<LightStrategy>("--lights", kLightStrategyNames, lights);
  if (!reuse.empty()) o.render.reuse = parse_enum<ReuseMode>("--reuse", kReuseModeNames, reuse);
  if (!accel.empty()) o.accel = parse_enum<AccelKind>("--accel", kAccelKindNames, accel);
  if (o.accel == AccelKind::kEmbree && !embree_available())
    throw UsageError("--accel embree: this build has no Embree (install libembree-dev and rebuild)");
  if (!view.empty() && view != "combined") o.view = parse_enum<Layer>("--view", kLayerNames, view);
  if (!tonemap.empty()) o.display.tonemap = parse_enum<ToneMap>("--tonemap", kToneMapNames, tonemap);
  if (smooth == "on")
    o.smooth_normals = true;
  else if (smooth == "off")
    o.smooth_normals = false;
  else if (!smooth.empty())
    throw UsageError("--smooth-normals: '" + smooth + "' is not on|off");
  if (!gl.empty()) o.gl = parse_enum<HeadlessGl>("--gl", kHeadlessGlNames, gl);
  if (o.headless && o.gl != HeadlessGl::kNone && !o.out_path.empty() && !ends_with_png(o.out_path))
    throw UsageError("--gl " + gl + " takes a screenshot: --out must be a .png file");
  if (o.ui && o.gl == HeadlessGl::kNone && o.headless)
    throw UsageError("--ui draws the panel through GL: add --gl egl|osmesa|auto");
  if (!camera.empty()) {
    const std::vector<float> v = parse_floats("--camera", camera, 7);
    CameraSpec spec;
    spec.eye = Vec3(v[0], v[1], v[2]);
    spec.target = Vec3(v[3], v[4], v[5]);
    spec.fovy_degrees = v[6];
    if (!(v[6] > 0.0f && v[6] < 180.0f)) throw UsageError("--camera: field of view must be in (0, 180) degrees");
    if (spec.eye == spec.target) throw UsageError("--camera: eye and target are the same point");
    o.camera = spec;
  }
  if (!up.empty()) {
    const std::vector<float> v = parse_floats("--up", up, 3);
    if (v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f) throw UsageError("--up: the zero vector has no direction");
    o.up = Vec3(v[0], v[1], v[2]);
  }
  if (o.headless && o.out_path.empty() && o.export_default_scene.empty())
    throw UsageError("--headless needs --out FILE");
  return o;
}

std::string describe_options(const AppOptions& o) {
  std::ostringstream s;
  s << "lueur ";
  if (!o.scene_path.empty()) s << "'" << o.scene_path << "' ";
  s << "--size " << o.render.width << "x" << o.render.height << " --frames " << o.frames << " --passes ";
  bool first = true;
  for (int p = 0; p < kPassCount; ++p)
    if (o.render.enabled[static_cast<size_t>(p)]) {
      s << (first ? "" : ",") << kPassNames[static_cast<size_t>(p)];
      first = false;
    }
  s << " --weights ";
  for (int p = 0; p < kPassCount; ++p)
    s << (p ? "," : "") << kPassNames[static_cast<size_t>(p)] << "=" << o.weights[static_cast<size_t>(p)];
  s << " --lights " << enum_name(kLightStrategyNames, o.render.lights) << " --l1-rays " << o.render.l1_rays
    << " --l2-rays " << o.render.l2_rays << " --reuse " << enum_name(kReuseModeNames, o.render.reuse)
    << " --recompute-ratio " << o.render.recompute_ratio << (o.render.reuse_diffuse_only ? " --reuse-diffuse-only" : "")
    << " --ao-rays " << o.render.ao_rays;
  if (o.render.ao_radius > 0.0f) s << " --ao-radius " << o.render.ao_radius;
  if (o.view) s << " --view " << enum_name(kLayerNames, *o.view);
  if (o.accel != AccelKind::kLueur) s << " --accel " << enum_name(kAccelKindNames, o.accel);
  s << " --blinn-k " << o.render.blinn_k << " --smooth-normals " << (o.smooth_normals ? "on" : "off") << " --seed "
    << o.render.seed << " --exposure " << o.display.exposure << " --tonemap "
    << enum_name(kToneMapNames, o.display.tonemap);
  if (o.camera)
    s << " --camera \"" << o.camera->eye.x << " " << o.camera->eye.y << " " << o.camera->eye.z << " "
      << o.camera->target.x << " " << o.camera->target.y << " " << o.camera->target.z << " " << o.camera->fovy_degrees
      << "\"";
  if (o.up) s << " --up \"" << o.up->x << " " << o.up->y << " " << o.up->z << "\"";
  return s.str();
}

}  // namespace lueur
