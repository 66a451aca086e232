// Shader compilation, texture uploads and the full-screen draw of the display.
#include "display/display_pipeline.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "display/shader_sources.h"
#include "film/noise_view.h"

namespace lueur {
namespace {

unsigned compile_shader(const GlApi& gl, GLenum kind, const char* source) {
  const unsigned shader = gl.CreateShader(kind);
  gl.ShaderSource(shader, 1, &source, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl.DeleteShader(shader);
    throw std::runtime_error(std::string("display shader does not compile: ") + log);
  }
  return shader;
}

unsigned link_program(const GlApi& gl) {
  const unsigned vs = compile_shader(gl, GL_VERTEX_SHADER, kDisplayVertexShader);
  const unsigned fs = compile_shader(gl, GL_FRAGMENT_SHADER, kDisplayFragmentShader);
  const unsigned program = gl.CreateProgram();
  gl.AttachShader(program, vs);
  gl.AttachShader(program, fs);
  gl.LinkProgram(program);
  gl.DeleteShader(vs);
  gl.DeleteShader(fs);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    gl.GetProgramInfoLog(program, sizeof log, nullptr, log);
    gl.DeleteProgram(program);
    throw std::runtime_error(std::string("display shaders do not link: ") + log);
  }
  return program;
}

}  // namespace

DisplayPipeline::DisplayPipeline(const GlApi& gl) : gl_(gl) {
  program_ = link_program(gl_);
  // Sampler s always reads texture unit s.
  gl_.UseProgram(program_);
  for (int s = 0; s < 4; ++s) {
    const std::string name = "u_slot" + std::to_string(s);
    gl_.Uniform1i(gl_.GetUniformLocation(program_, name.c_str()), s);
  }
  gl_.UseProgram(0);
  uniforms_ = {gl_.GetUniformLocation(program_, "u_scale"), gl_.GetUniformLocation(program_, "u_exposure"),
               gl_.GetUniformLocation(program_, "u_tonemap"), gl_.GetUniformLocation(program_, "u_rect")};
  gl_.GenVertexArrays(1, &vertex_array_);
  for (Slot& slot : slots_) {
    gl_.GenTextures(1, &slot.texture);
    gl_.BindTexture(GL_TEXTURE_2D, slot.texture);
    // Nearest: a texel is a pixel of the film, so the off-screen image reproduces the CPU's exactly, and a
    // reduced-resolution preview shows as honest blocks.
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const float black[3] = {0.0f, 0.0f, 0.0f};
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, 1, 1, 0, GL_RGB, GL_FLOAT, black);
  }
}

DisplayPipeline::~DisplayPipeline() {
  for (Slot& slot : slots_) gl_.DeleteTextures(1, &slot.texture);
  gl_.DeleteVertexArrays(1, &vertex_array_);
  gl_.DeleteProgram(program_);
}

std::array<int, 4> DisplayPipeline::slot_layers(const Settings& shown) const {
  std::array<int, 4> layers = {-1, -1, -1, -1};
  if (shown.layer) {
    layers[0] = static_cast<int>(*shown.layer);
    return layers;
  }
  for (int p = 0; p < kPassCount; ++p)
    if (shown.render.enabled[static_cast<size_t>(p)])
      layers[static_cast<size_t>(p)] = static_cast<int>(layer_of(static_cast<Pass>(p)));
  return layers;
}

void DisplayPipeline::update(const Film& film, uint64_t film_version, const Settings& shown) {
  width_ = film.width;
  height_ = film.height;
  frames_ = film.frames;
  for (int l = 0; l < kLayerCount; ++l) film_has_[static_cast<size_t>(l)] = film.has(static_cast<Layer>(l));
  if (shown.show_noise) {
    // The noise view is made on the CPU (it needs the whole film) and shown as it is.
    Slot& slot = slots_[0];
    const uint64_t weights_key = std::hash<std::string_view>{}(
        std::string_view(reinterpret_cast<const char*>(shown.weights.data()), sizeof(float) * shown.weights.size()));
    if (slot.layer == kNoiseView && slot.version == film_version && slot.key == weights_key &&
        slot.width == film.width && slot.height == film.height)
      return;
    const Image view = noise_view_image(film, shown.render.enabled, shown.weights, shown.render.sampler);
    upload(slot, view.rgb.data(), film.width, film.height);
    slot.layer = kNoiseView;
    slot.version = film_version;
    slot.key = weights_key;
    return;
  }
  const std::array<int, 4> layers = slot_layers(shown);
  for (size_t s = 0; s < slots_.size(); ++s) {
    Slot& slot = slots_[s];
    const int layer = layers[s];
    if (layer < 0 || !film.has(static_cast<Layer>(layer))) continue;
    if (slot.layer == layer && slot.version == film_version && slot.width == film.width && slot.height == film.height)
      continue;
    upload(slot, film.sums[static_cast<size_t>(layer)].data(), film.width, film.height);
    slot.layer = layer;
    slot.version = film_version;
  }
}

void DisplayPipeline::upload(Slot& slot, const float* rgb, int width, int height) {
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl_.BindTexture(GL_TEXTURE_2D, slot.texture);
  if (slot.width == width && slot.height == height)
    gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_FLOAT, rgb);
  else
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width, height, 0, GL_RGB, GL_FLOAT, rgb);
  slot.width = width;
  slot.height = height;
}

void DisplayPipeline::draw(const Settings& shown, const PixelRect& viewport, const PixelRect& image,
                           const std::optional<PixelRect>& clip) const {
  const std::array<int, 4> layers = slot_layers(shown);
  float scale[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  DisplaySettings transform = shown.display;
  if (shown.show_noise) {
    transform = DisplaySettings{};  // false colours, not light: no exposure, no tone map
    const Slot& slot = slots_[0];
    if (slot.layer == kNoiseView && slot.width == width_ && slot.height == height_) scale[0] = 1.0f;
  }
  for (size_t s = 0; s < 4 && !shown.show_noise; ++s) {
    const int layer = layers[s];
    // A slot counts only when it holds this very layer of the current film.
    if (layer < 0 || frames_ == 0 || slots_[s].layer != layer || !film_has_[static_cast<size_t>(layer)] ||
        slots_[s].width != width_ || slots_[s].height != height_)
      continue;
    const float weight = shown.layer ? 1.0f : shown.weights[s];
    scale[s] = weight / static_cast<float>(frames_);
  }
  gl_.Viewport(viewport.x, viewport.y, viewport.width, viewport.height);
  gl_.Disable(GL_BLEND);
  if (clip) {
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(clip->x, clip->y, clip->width, clip->height);
  } else {
    gl_.Disable(GL_SCISSOR_TEST);
  }
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.UseProgram(program_);
  for (int s = 0; s < 4; ++s) {
    gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + s));
    gl_.BindTexture(GL_TEXTURE_2D, slots_[static_cast<size_t>(s)].texture);
  }
  gl_.Uniform4f(uniforms_.scale, scale[0], scale[1], scale[2], scale[3]);
  gl_.Uniform1f(uniforms_.exposure, transform.exposure);
  gl_.Uniform1i(uniforms_.tonemap, static_cast<int>(transform.tonemap));
  // gl_FragCoord is in window coordinates, so the rectangle is too.
  gl_.Uniform4f(uniforms_.rect, static_cast<float>(image.x), static_cast<float>(image.y),
                static_cast<float>(image.width), static_cast<float>(image.height));
  gl_.BindVertexArray(vertex_array_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  gl_.BindVertexArray(0);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.Disable(GL_SCISSOR_TEST);
}

}  // namespace lueur
