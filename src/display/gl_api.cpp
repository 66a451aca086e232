// Fills the GL function table from a context's get-proc-address.
#include "display/gl_api.h"

#include <stdexcept>

namespace lueur {

GlApi load_gl_api(GlGetProcAddress get_proc) {
  GlApi gl;
#define LUEUR_GL_LOAD(name, type)                         \
  gl.name = reinterpret_cast<type>(get_proc("gl" #name)); \
  if (!gl.name) throw std::runtime_error("OpenGL function gl" #name " is missing");
  LUEUR_GL_FUNCTIONS(LUEUR_GL_LOAD)
#undef LUEUR_GL_LOAD
  return gl;
}

std::string describe_gl_context(const GlApi& gl) {
  const auto text = [&](GLenum what) {
    const GLubyte* s = gl.GetString(what);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
}

}  // namespace lueur
