// JSON form of a view. Every value read is checked: a view file is input like any other.
#include "render/view_state.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/atomic_file.h"

namespace lueur {
namespace {

using nlohmann::json;

json vec_to_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

template <size_t N>
std::string names_list(const std::array<std::string_view, N>& names) {
  std::string s;
  for (const auto n : names) {
    if (!s.empty()) s += '|';
    s += n;
  }
  return s;
}

/// Reads helpers: each throws ViewFileError naming the field.
struct Reader {
  const json& root;

  const json* find(const char* key) const {
    const auto it = root.find(key);
    return it == root.end() ? nullptr : &*it;
  }
  float number(const json& value, const std::string& field, float lo, float hi) const {
    if (!value.is_number()) throw ViewFileError("view file: '" + field + "' is not a number");
    const double v = value.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi)
      throw ViewFileError("view file: '" + field + "' = " + value.dump() + " is outside [" + json(lo).dump() + ", " +
                          json(hi).dump() + "]");
    return static_cast<float>(v);
  }
  void read_float(const char* key, float& out, float lo, float hi) const {
    if (const json* v = find(key)) out = number(*v, key, lo, hi);
  }
  void read_int(const char* key, int& out, int lo, int hi) const {
    if (const json* v = find(key)) {
      if (!v->is_number_integer()) throw ViewFileError(std::string("view file: '") + key + "' is not an integer");
      const int64_t i = v->get<int64_t>();
      if (i < lo || i > hi)
        throw ViewFileError(std::string("view file: '") + key + "' = " + v->dump() + " is outside [" +
                            std::to_string(lo) + ", " + std::to_string(hi) + "]");
      out = static_cast<int>(i);
    }
  }
  void read_bool(const char* key, bool& out) const {
    if (const json* v = find(key)) {
      if (!v->is_boolean()) throw ViewFileError(std::string("view file: '") + key + "' is not true or false");
      out = v->get<bool>();
    }
  }
  Vec3 vec3(const json& value, const std::string& field) const {
    if (!value.is_array() || value.size() != 3)
      throw ViewFileError("view file: '" + field + "' is not an array of 3 numbers");
    const float lim = 1e30f;
    return Vec3(number(value[0], field, -lim, lim), number(value[1], field, -lim, lim),
                number(value[2], field, -lim, lim));
  }
  template <typename Enum, size_t N>
  void read_enum(const char* key, const std::array<std::string_view, N>& names, Enum& out) const {
    if (const json* v = find(key)) {
      if (!v->is_string()) throw ViewFileError(std::string("view file: '") + key + "' is not a string");
      const auto e = enum_from_name<Enum>(names, v->get<std::string>());
      if (!e)
        throw ViewFileError(std::string("view file: '") + key + "' = " + v->dump() + " is not one of " +
                            names_list(names));
      out = *e;
    }
  }
};

}  // namespace

std::string view_to_json(const ViewState& v) {
  json passes = json::array(), weights = json::object();
  for (int p = 0; p < kPassCount; ++p) {
    const std::string name(kPassNames[static_cast<size_t>(p)]);
    if (v.render.enabled[static_cast<size_t>(p)]) passes.push_back(name);
    weights[name] = v.weights[static_cast<size_t>(p)];
  }
  json j = {
      {"lueur_view", 1},
      {"width", v.render.width},
      {"height", v.render.height},
      {"passes", passes},
      {"weights", weights},
      {"lights", std::string(enum_name(kLightStrategyNames, v.render.lights))},
      {"l1_rays", v.render.l1_rays},
      {"blinn_k", v.render.blinn_k},
      {"l2_rays", v.render.l2_rays},
      {"reuse", std::string(enum_name(kReuseModeNames, v.render.reuse))},
      {"recompute_ratio", v.render.recompute_ratio},
      {"reuse_diffuse_only", v.render.reuse_diffuse_only},
      {"ao_rays", v.render.ao_rays},
      {"ao_radius", v.render.ao_radius},
      {"seed", v.render.seed},
      {"view", v.layer ? std::string(enum_name(kLayerNames, *v.layer)) : std::string("combined")},
      {"exposure", v.display.exposure},
      {"tonemap", std::string(enum_name(kToneMapNames, v.display.tonemap))},
      {"smooth_normals", v.smooth_normals},
      {"frame_limit", v.frame_limit},
      {"frames", v.frames},
  };
  if (v.camera)
    j["camera"] = {{"eye", vec_to_json(v.camera->eye)},
                   {"target", vec_to_json(v.camera->target)},
                   {"up", vec_to_json(v.camera->up)},
                   {"fovy_degrees", v.camera->fovy_degrees}};
  return j.dump(2) + "\n";
}

ViewState view_from_json(const std::string& text, const ViewState& defaults) {
  const json root = json::parse(text, nullptr, false);
  if (root.is_discarded()) throw ViewFileError("view file: not valid JSON");
  if (!root.is_object() || !root.contains("lueur_view"))
    throw ViewFileError("view file: not a Lueur view (no 'lueur_view')");
  ViewState v = defaults;
  const Reader r{root};
  if (const json* camera = r.find("camera")) {
    if (!camera->is_object()) throw ViewFileError("view file: 'camera' is not an object");
    const Reader c{*camera};
    CameraSpec spec = v.camera.value_or(CameraSpec{});
    if (const json* e = c.find("eye")) spec.eye = c.vec3(*e, "camera.eye");
    if (const json* t = c.find("target")) spec.target = c.vec3(*t, "camera.target");
    if (const json* u = c.find("up")) spec.up = c.vec3(*u, "camera.up");
    c.read_float("fovy_degrees", spec.fovy_degrees, 1e-3f, 179.0f);
    if (spec.eye == spec.target) throw ViewFileError("view file: camera eye and target are the same point");
    if (spec.up == Vec3(0.0f)) throw ViewFileError("view file: camera up is the zero vector");
    v.camera = spec;
  }
  r.read_int("width", v.render.width, 1, 16384);
  r.read_int("height", v.render.height, 1, 16384);
  if (const json* passes = r.find("passes")) {
    if (!passes->is_array()) throw ViewFileError("view file: 'passes' is not an array");
    v.render.enabled.fill(false);
    for (const json& p : *passes) {
      const auto pass = p.is_string() ? enum_from_name<Pass>(kPassNames, p.get<std::string>()) : std::nullopt;
      if (!pass) throw ViewFileError("view file: 'passes' has " + p.dump() + ", not one of " + names_list(kPassNames));
      v.render.enabled[static_cast<size_t>(*pass)] = true;
    }
  }
  if (const json* weights = r.find("weights")) {
    if (!weights->is_object()) throw ViewFileError("view file: 'weights' is not an object");
    for (const auto& [name, value] : weights->items()) {
      const auto pass = enum_from_name<Pass>(kPassNames, name);
      if (!pass) throw ViewFileError("view file: 'weights' has unknown pass '" + name + "'");
      v.weights[static_cast<size_t>(*pass)] = r.number(value, "weights." + name, -1e6f, 1e6f);
    }
  }
  r.read_enum("lights", kLightStrategyNames, v.render.lights);
  r.read_int("l1_rays", v.render.l1_rays, 0, 4096);
  r.read_float("blinn_k", v.render.blinn_k, 0.0f, 1.0f);
  r.read_int("l2_rays", v.render.l2_rays, 0, 4096);
  r.read_enum("reuse", kReuseModeNames, v.render.reuse);
  r.read_float("recompute_ratio", v.render.recompute_ratio, 0.0f, 16.0f);
  r.read_bool("reuse_diffuse_only", v.render.reuse_diffuse_only);
  r.read_int("ao_rays", v.render.ao_rays, 0, 4096);
  r.read_float("ao_radius", v.render.ao_radius, 0.0f, 1e30f);
  if (const json* seed = r.find("seed")) {
    if (!seed->is_number_unsigned() && !(seed->is_number_integer() && seed->get<int64_t>() >= 0))
      throw ViewFileError("view file: 'seed' is not a non-negative integer");
    v.render.seed = seed->get<uint64_t>();
  }
  if (const json* layer = r.find("view")) {
    if (!layer->is_string()) throw ViewFileError("view file: 'view' is not a string");
    const std::string name = layer->get<std::string>();
    if (name == "combined") {
      v.layer.reset();
    } else {
      const auto l = enum_from_name<Layer>(kLayerNames, name);
      if (!l) throw ViewFileError("view file: 'view' = '" + name + "' is not combined|" + names_list(kLayerNames));
      v.layer = *l;
    }
  }
  r.read_float("exposure", v.display.exposure, -30.0f, 30.0f);
  r.read_enum("tonemap", kToneMapNames, v.display.tonemap);
  r.read_bool("smooth_normals", v.smooth_normals);
  for (const auto& [key, out] : {std::pair<const char*, uint64_t*>{"frame_limit", &v.frame_limit},
                                 std::pair<const char*, uint64_t*>{"frames", &v.frames}})
    if (const json* count = r.find(key)) {
      if (!count->is_number_integer() || count->get<int64_t>() < 0)
        throw ViewFileError(std::string("view file: '") + key + "' is not a non-negative integer");
      *out = count->get<uint64_t>();
    }
  return v;
}

void save_view_file(const std::string& path, const ViewState& view) { write_file_atomically(path, view_to_json(view)); }

ViewState load_view_file(const std::string& path, const ViewState& defaults) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read view file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return view_from_json(text.str(), defaults);
  } catch (const ViewFileError& e) {
    throw ViewFileError(path + ": " + e.what());
  }
}

}  // namespace lueur
