// OpenGL contexts without a window, for screenshots on machines with no display: Mesa's EGL surfaceless platform
// (llvmpipe on the CPU) or, where EGL is missing, OSMesa. Each lives in its own .cpp because osmesa.h and the EGL
// headers do not mix with glcorearb.h.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>

#include "display/gl_proc.h"

namespace lueur {

enum class HeadlessGl : int { kNone = 0, kEgl = 1, kOsmesa = 2, kAuto = 3 };
inline constexpr std::array<std::string_view, 4> kHeadlessGlNames = {"none", "egl", "osmesa", "auto"};

/// A current OpenGL 3.3+ core context; destroying it releases the context.
struct HeadlessContext {
  GlGetProcAddress get_proc = nullptr;
  std::string kind;              ///< "EGL surfaceless" or "OSMesa"
  std::shared_ptr<void> handle;  ///< owns the platform objects
};

/// Creates and makes current an EGL surfaceless context. Throws std::runtime_error saying what failed.
HeadlessContext create_egl_context();
/// Creates and makes current an OSMesa context. Throws std::runtime_error saying what failed.
HeadlessContext create_osmesa_context();
/// kEgl, kOsmesa, or kAuto (EGL, then OSMesa; the error names both failures when neither works).
HeadlessContext create_headless_context(HeadlessGl kind);

}  // namespace lueur
