// OSMesa: Mesa's software renderer into a client buffer, the fallback where EGL is missing.
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

#include "display/headless_context.h"

namespace lueur {
namespace {

/// OSMesa needs a buffer to make a context current; the display renders into its own framebuffer object.
constexpr int kBufferSize = 16;

struct OsmesaObjects {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer = std::vector<unsigned char>(4 * kBufferSize * kBufferSize);
  ~OsmesaObjects() {
    if (context) OSMesaDestroyContext(context);
  }
};

GlProc osmesa_get_proc(const char* name) { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); }

}  // namespace

HeadlessContext create_osmesa_context() {
  auto objects = std::make_shared<OsmesaObjects>();
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  objects->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!objects->context) throw std::runtime_error("OSMesa: cannot create a 3.3 core context");
  if (!OSMesaMakeCurrent(objects->context, objects->buffer.data(), GL_UNSIGNED_BYTE, kBufferSize, kBufferSize))
    throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
  return HeadlessContext{osmesa_get_proc, "OSMesa", objects};
}

}  // namespace lueur
