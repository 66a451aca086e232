// EGL on Mesa's surfaceless platform: no X server, no GPU, no environment variables needed.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <stdexcept>
#include <string>

#include "display/headless_context.h"

namespace lueur {
namespace {

struct EglObjects {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  ~EglObjects() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

GlProc egl_get_proc(const char* name) { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); }

std::string egl_error(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string("EGL: ") + what + " failed (error " + code + ")";
}

}  // namespace

HeadlessContext create_egl_context() {
  // The explicit platform call: eglGetDisplay(EGL_DEFAULT_DISPLAY) would try X11 and fail without a server.
  const auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is not available");
  auto objects = std::make_shared<EglObjects>();
  objects->display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (objects->display == EGL_NO_DISPLAY)
    throw std::runtime_error("EGL: no surfaceless display (is Mesa's libegl-mesa0 installed?)");
  EGLint major = 0, minor = 0;
  if (!eglInitialize(objects->display, &major, &minor)) {
    objects->display = EGL_NO_DISPLAY;
    throw std::runtime_error(egl_error("eglInitialize"));
  }
  if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(egl_error("eglBindAPI(OpenGL)"));
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(objects->display, config_attributes, &config, 1, &configs) || configs < 1)
    throw std::runtime_error(egl_error("eglChooseConfig"));
  const EGLint context_attributes[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  objects->context = eglCreateContext(objects->display, config, EGL_NO_CONTEXT, context_attributes);
  if (objects->context == EGL_NO_CONTEXT) throw std::runtime_error(egl_error("eglCreateContext(3.3 core)"));
  if (!eglMakeCurrent(objects->display, EGL_NO_SURFACE, EGL_NO_SURFACE, objects->context))
    throw std::runtime_error(egl_error("eglMakeCurrent"));
  return HeadlessContext{egl_get_proc, "EGL surfaceless", objects};
}

}  // namespace lueur
