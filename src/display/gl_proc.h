// The get-proc-address signature every GL context kind provides; kept apart from gl_api.h so that files which
// include platform GL headers (osmesa.h pulls in GL/gl.h) need not see glcorearb.h too.
#pragma once

namespace lueur {

using GlProc = void (*)();
using GlGetProcAddress = GlProc (*)(const char* name);

}  // namespace lueur
