// The display shaders of shaders/, compiled into the program at build time (see shader_sources.cpp.in) so that the
// executable does not depend on where the source tree is.
#pragma once

namespace lueur {

extern const char* const kDisplayVertexShader;
extern const char* const kDisplayFragmentShader;

}  // namespace lueur
