// Conversions between the command-line options and a view (the form the window saves).
#include "app/options.h"

namespace lueur {

ViewState view_from_options(const AppOptions& o) {
  ViewState v;
  v.camera = o.camera;
  if (v.camera && o.up) v.camera->up = *o.up;
  v.render = o.render;
  v.weights = o.weights;
  v.layer = o.view;
  v.display = o.display;
  v.smooth_normals = o.smooth_normals;
  v.frame_limit = o.frame_limit;
  v.frames = static_cast<uint64_t>(o.frames);
  return v;
}

void apply_view(const ViewState& v, AppOptions& o) {
  o.camera = v.camera;
  if (v.camera) o.up = v.camera->up;
  o.render = v.render;
  o.weights = v.weights;
  o.view = v.layer;
  o.display = v.display;
  o.smooth_normals = v.smooth_normals;
  o.frame_limit = v.frame_limit;
  if (v.frames > 0) o.frames = static_cast<int>(std::min<uint64_t>(v.frames, 1000000));
}

}  // namespace lueur
