// The settings made of several values: the image size, the passes, their weights, the layer shown, the camera
// and its up vector. Each reads command-line text and its own view-file form, and checks both the same way.
#include <cmath>

#include "settings/compare.h"
#include "settings/setting_kinds.h"

namespace lueur::setting_rows {
namespace {

using nlohmann::json;

std::string vec_text(const Vec3& v) { return float_text(v.x) + " " + float_text(v.y) + " " + float_text(v.z); }
json vec_json(const Vec3& v) { return json::array({json_real(v.x), json_real(v.y), json_real(v.z)}); }

Vec3 vec_from_json(const json& value, const std::string& key) {
  if (!value.is_array() || value.size() != 3) throw ValueError(in_quotes(key) + " is not an array of 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    const json& c = value[static_cast<size_t>(i)];
    const std::optional<float> f = finite_float(number_json_text(c, key));
    if (!f) throw ValueError(in_quotes(key) + " has " + c.dump() + ", not a finite number");
    v[i] = *f;
  }
  return v;
}

void check_camera(const CameraSpec& camera) {
  if (!(camera.fovy_degrees > 0.0f && camera.fovy_degrees < 180.0f))
    throw ValueError("field of view " + float_text(camera.fovy_degrees) + " is outside (0, 180) degrees");
  if (camera.eye == camera.target) throw ValueError("eye and target are the same point");
  if (camera.up == Vec3(0.0f)) throw ValueError("up is the zero vector");
}

}  // namespace

Row size_row() {
  const SettingRange range{1, 16384};
  Row row = base_row("size", "WxH", "image size WIDTHxHEIGHT", SettingEffect::kRestart);
  row.info.range = range;
  row.parse = [range](Settings& s, const std::string& text) {
    const size_t x = text.find_first_of("xX");
    if (x == std::string::npos) throw ValueError(in_quotes(text) + " is not WIDTHxHEIGHT");
    const std::string w = text.substr(0, x), h = text.substr(x + 1);
    s.render.width = static_cast<int>(parse_signed(w, range));
    s.render.height = static_cast<int>(parse_signed(h, range));
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    return std::to_string(s.render.width) + "x" + std::to_string(s.render.height);
  };
  row.json_keys = {"width", "height"};
  row.write_json = [](const Settings& s, json& root) {
    root["width"] = s.render.width;
    root["height"] = s.render.height;
  };
  row.read_json = [range](const json& root, Settings& s) {
    for (const auto& [key, member] : {std::pair{"width", &RenderSettings::width}, {"height", &RenderSettings::height}})
      if (const auto it = root.find(key); it != root.end()) {
        if (!it->is_number_integer()) throw ValueError(in_quotes(key) + " is not an integer");
        try {
          s.render.*member = static_cast<int>(parse_signed(it->dump(), range));
        } catch (const ValueError& e) {
          throw ValueError(in_quotes(key) + ": " + e.what());
        }
      }
  };
  return row;
}

Row passes_row() {
  Row row = base_row("passes", "le,l1,l2,ao,ln", "the passes rendered, comma-separated", SettingEffect::kRestart);
  row.parse = [](Settings& s, const std::string& text) {
    s.render.enabled.fill(false);
    for (const std::string& name : split(text, ',')) {
      const std::optional<Pass> pass = enum_from_name<Pass>(kPassNames, name);
      if (!pass) throw ValueError(in_quotes(name) + " is not one of " + names_list(kPassNames));
      s.render.enabled[static_cast<size_t>(*pass)] = true;
    }
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    std::string text;
    for (size_t p = 0; p < kPassCount; ++p)
      if (s.render.enabled[p]) append_listed(text, kPassNames[p], ',');
    return text;
  };
  row.write_json = [](const Settings& s, json& root) {
    json passes = json::array();
    for (size_t p = 0; p < kPassCount; ++p)
      if (s.render.enabled[p]) passes.push_back(std::string(kPassNames[p]));
    root["passes"] = passes;
  };
  row.read_json = [parse = row.parse](const json& root, Settings& s) {
    const auto it = root.find("passes");
    if (it == root.end()) return;
    if (!it->is_array()) throw ValueError("'passes' is not an array");
    std::string text;
    for (const json& p : *it) {
      if (!p.is_string()) throw ValueError("'passes' has " + p.dump() + ", not one of " + names_list(kPassNames));
      append_listed(text, p.get<std::string>(), ',');
    }
    try {
      parse(s, text);
    } catch (const ValueError& e) {
      throw ValueError(std::string("'passes': ") + e.what());
    }
  };
  return row;
}

Row weights_row() {
  const SettingRange range{-1e6, 1e6}, slider{0, 2};
  Row row = base_row("weights", "le=W,l1=W,...", "pass weights in the image: sum of weight x average(pass)",
                     SettingEffect::kDisplay);
  row.info.range = range;
  row.info.slider = slider;
  const auto set_weight = [range](Settings& s, const std::string& pass_name, const std::string& value) {
    const std::optional<Pass> pass = enum_from_name<Pass>(kPassNames, pass_name);
    if (!pass) throw ValueError(in_quotes(pass_name) + " is not one of " + names_list(kPassNames));
    s.weights[static_cast<size_t>(*pass)] = parse_real(value, range);
  };
  row.parse = [set_weight](Settings& s, const std::string& text) {
    for (const std::string& item : split(text, ',')) {
      const size_t eq = item.find('=');
      if (eq == std::string::npos) throw ValueError(in_quotes(item) + " is not PASS=WEIGHT");
      set_weight(s, item.substr(0, eq), item.substr(eq + 1));
    }
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    std::string text;
    for (size_t p = 0; p < kPassCount; ++p)
      append_listed(text, std::string(kPassNames[p]) + "=" + float_text(s.weights[p]), ',');
    return text;
  };
  row.write_json = [](const Settings& s, json& root) {
    json weights = json::object();
    for (size_t p = 0; p < kPassCount; ++p) weights[std::string(kPassNames[p])] = json_real(s.weights[p]);
    root["weights"] = weights;
  };
  row.read_json = [set_weight](const json& root, Settings& s) {
    const auto it = root.find("weights");
    if (it == root.end()) return;
    if (!it->is_object()) throw ValueError("'weights' is not an object");
    for (const auto& [name, value] : it->items()) {
      try {
        set_weight(s, name, number_json_text(value, "weights." + name));
      } catch (const ValueError& e) {
        throw ValueError("'weights." + name + "': " + e.what());
      }
    }
  };
  return row;
}

/// The layer shown: `combined` (the weighted passes) or one layer.
Row view_row() {
  static const std::string value_name = "combined|" + names_list(kLayerNames) + "|noise";
  Row row = base_row("view", value_name,
                     "what is shown: the weighted combination of the passes, a pass, a layer that explains reuse, or "
                     "the combined image's estimated relative error per pixel in false colour",
                     SettingEffect::kDisplay);
  row.always_described = false;
  row.parse = [](Settings& s, const std::string& text) {
    s.show_noise = text == "noise";
    if (text == "combined" || s.show_noise) {
      s.layer.reset();
      return;
    }
    const std::optional<Layer> layer = enum_from_name<Layer>(kLayerNames, text);
    if (!layer) throw ValueError(in_quotes(text) + " is not one of " + value_name);
    s.layer = *layer;
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    if (s.show_noise) return "noise";
    return s.layer ? std::string(enum_name(kLayerNames, *s.layer)) : "combined";
  };
  row.write_json = [format = row.format](const Settings& s, json& root) { root["view"] = *format(s); };
  read_json_through_text(row, string_json_text);
  return row;
}

/// The A/B comparison: one setting that changes the estimate, and the value the split's right side gives it.
Row compare_row() {
  Row row = base_row("compare", "SETTING=VALUE",
                     "A/B split view: the right side renders with this one setting changed (e.g. lights=uniform, "
                     "reuse=off, sampler=independent), both sides accumulating at once; empty: no split",
                     SettingEffect::kRestart);
  row.always_described = false;
  row.parse = [](Settings& s, const std::string& text) {
    if (text.empty()) {
      s.compare.clear();
      return;
    }
    const size_t equals = text.find('=');
    if (equals == std::string::npos) throw ValueError(in_quotes(text) + " is not SETTING=VALUE (e.g. lights=uniform)");
    const std::string name = text.substr(0, equals);
    if (!comparable(name)) throw ValueError(in_quotes(name) + " cannot be compared: use one of " + comparable_list());
    Settings trial = s;
    try {
      set_setting(trial, name, text.substr(equals + 1));
    } catch (const SettingError& e) {
      throw ValueError(e.what());
    }
    s.compare = text;
  };
  row.format = [](const Settings& s) -> std::optional<std::string> { return s.compare; };
  row.write_json = [](const Settings& s, json& root) { root["compare"] = s.compare; };
  read_json_through_text(row, string_json_text);
  return row;
}

Row camera_row() {
  Row row = base_row("camera", "\"ex ey ez tx ty tz fovy\"|inside|outside",
                     "eye, target and vertical field of view in degrees, or the scene's view from inside a closed "
                     "room or from outside (default: the scene's view)",
                     SettingEffect::kRestart);
  row.parse = [](Settings& s, const std::string& text) {
    // A named view instead of numbers: the scene's own view from inside or outside (the start-view setting).
    for (size_t k = 0; k < kStartViewNames.size(); ++k) {
      if (text != kStartViewNames[k]) continue;
      s.camera.reset();
      s.start_view = static_cast<StartView>(k);
      return;
    }
    const std::vector<float> v = parse_reals(text, 7);
    CameraSpec camera = s.camera.value_or(CameraSpec{});  // a new eye and target keep the camera's up
    camera.eye = Vec3(v[0], v[1], v[2]);
    camera.target = Vec3(v[3], v[4], v[5]);
    camera.fovy_degrees = v[6];
    check_camera(camera);
    s.camera = camera;
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    if (!s.camera) return std::nullopt;
    return vec_text(s.camera->eye) + " " + vec_text(s.camera->target) + " " + float_text(s.camera->fovy_degrees);
  };
  row.same = [](const Settings& a, const Settings& b) { return a.camera == b.camera; };
  row.write_json = [](const Settings& s, json& root) {
    if (!s.camera) return;
    root["camera"] = {{"eye", vec_json(s.camera->eye)},
                      {"target", vec_json(s.camera->target)},
                      {"up", vec_json(s.camera->up)},
                      {"fovy_degrees", json_real(s.camera->fovy_degrees)}};
  };
  row.read_json = [](const json& root, Settings& s) {
    const auto it = root.find("camera");
    if (it == root.end()) return;
    if (!it->is_object()) throw ValueError("'camera' is not an object");
    CameraSpec camera = s.camera.value_or(CameraSpec{});
    for (const auto& [key, member] :
         {std::pair{"eye", &CameraSpec::eye}, {"target", &CameraSpec::target}, {"up", &CameraSpec::up}})
      if (const auto v = it->find(key); v != it->end())
        camera.*member = vec_from_json(*v, "camera." + std::string(key));
    if (const auto fovy = it->find("fovy_degrees"); fovy != it->end()) {
      const std::optional<float> f = finite_float(number_json_text(*fovy, "camera.fovy_degrees"));
      if (!f) throw ValueError("'camera.fovy_degrees' is not a finite number");
      camera.fovy_degrees = *f;
    }
    try {
      check_camera(camera);
    } catch (const ValueError& e) {
      throw ValueError(std::string("'camera': ") + e.what());
    }
    s.camera = camera;
  };
  return row;
}

/// The up vector: an override for whichever camera is used. Its text also shows a camera's own up when that is
/// not +y, so that the settings written into an image reproduce a camera loaded from a view file.
Row up_row() {
  Row row = base_row("up", "\"x y z\"", "the camera's up vector (default 0 1 0)", SettingEffect::kRestart);
  row.parse = [](Settings& s, const std::string& text) {
    const std::vector<float> v = parse_reals(text, 3);
    if (v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f) throw ValueError("the zero vector has no direction");
    s.up = Vec3(v[0], v[1], v[2]);
  };
  row.format = [](const Settings& s) -> std::optional<std::string> {
    if (s.up) return vec_text(*s.up);
    if (s.camera && s.camera->up != CameraSpec{}.up) return vec_text(s.camera->up);
    return std::nullopt;
  };
  row.same = [](const Settings& a, const Settings& b) { return a.up == b.up; };
  row.write_json = [](const Settings& s, json& root) {
    if (s.up) root["up"] = vec_json(*s.up);
  };
  row.read_json = [](const json& root, Settings& s) {
    const auto it = root.find("up");
    if (it == root.end()) return;
    const Vec3 up = vec_from_json(*it, "up");
    if (up == Vec3(0.0f)) throw ValueError("'up' is the zero vector");
    s.up = up;
  };
  return row;
}

}  // namespace lueur::setting_rows
