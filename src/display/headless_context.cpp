// Picks the headless context kind, falling back from EGL to OSMesa.
#include "display/headless_context.h"

#include <stdexcept>

namespace lueur {

HeadlessContext create_headless_context(HeadlessGl kind) {
  switch (kind) {
    case HeadlessGl::kEgl:
      return create_egl_context();
    case HeadlessGl::kOsmesa:
      return create_osmesa_context();
    case HeadlessGl::kAuto: {
      std::string egl_failure;
      try {
        return create_egl_context();
      } catch (const std::runtime_error& e) {
        egl_failure = e.what();
      }
      try {
        return create_osmesa_context();
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(egl_failure + "; " + e.what());
      }
    }
    case HeadlessGl::kNone:
      break;
  }
  throw std::runtime_error("no headless OpenGL context requested");
}

}  // namespace lueur
