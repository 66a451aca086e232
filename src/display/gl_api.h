// The OpenGL 3.3 core functions the display uses, loaded through the current context's get-proc-address into one
// table. Going through a table (never the gl* symbols of whichever libGL comes first on the link line) is what lets
// the same code draw into a GLFW window, an EGL surfaceless context and an OSMesa buffer.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "display/gl_proc.h"

namespace lueur {

// X-macro: one line per function, name without the gl prefix and its glcorearb.h pointer type.
#define LUEUR_GL_FUNCTIONS(X)                                \
  X(ActiveTexture, PFNGLACTIVETEXTUREPROC)                   \
  X(AttachShader, PFNGLATTACHSHADERPROC)                     \
  X(BindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)               \
  X(BindTexture, PFNGLBINDTEXTUREPROC)                       \
  X(BindVertexArray, PFNGLBINDVERTEXARRAYPROC)               \
  X(CheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC) \
  X(Clear, PFNGLCLEARPROC)                                   \
  X(ClearColor, PFNGLCLEARCOLORPROC)                         \
  X(CompileShader, PFNGLCOMPILESHADERPROC)                   \
  X(CreateProgram, PFNGLCREATEPROGRAMPROC)                   \
  X(CreateShader, PFNGLCREATESHADERPROC)                     \
  X(DeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)         \
  X(DeleteProgram, PFNGLDELETEPROGRAMPROC)                   \
  X(DeleteShader, PFNGLDELETESHADERPROC)                     \
  X(DeleteTextures, PFNGLDELETETEXTURESPROC)                 \
  X(DeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)         \
  X(Disable, PFNGLDISABLEPROC)                               \
  X(DrawArrays, PFNGLDRAWARRAYSPROC)                         \
  X(Enable, PFNGLENABLEPROC)                                 \
  X(Finish, PFNGLFINISHPROC)                                 \
  X(FramebufferTexture2D, PFNGLFRAMEBUFFERTEXTURE2DPROC)     \
  X(GenFramebuffers, PFNGLGENFRAMEBUFFERSPROC)               \
  X(GenTextures, PFNGLGENTEXTURESPROC)                       \
  X(GenVertexArrays, PFNGLGENVERTEXARRAYSPROC)               \
  X(GetError, PFNGLGETERRORPROC)                             \
  X(GetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)           \
  X(GetProgramiv, PFNGLGETPROGRAMIVPROC)                     \
  X(GetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)             \
  X(GetShaderiv, PFNGLGETSHADERIVPROC)                       \
  X(GetString, PFNGLGETSTRINGPROC)                           \
  X(GetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)         \
  X(LinkProgram, PFNGLLINKPROGRAMPROC)                       \
  X(PixelStorei, PFNGLPIXELSTOREIPROC)                       \
  X(ReadPixels, PFNGLREADPIXELSPROC)                         \
  X(Scissor, PFNGLSCISSORPROC)                               \
  X(ShaderSource, PFNGLSHADERSOURCEPROC)                     \
  X(TexImage2D, PFNGLTEXIMAGE2DPROC)                         \
  X(TexParameteri, PFNGLTEXPARAMETERIPROC)                   \
  X(TexSubImage2D, PFNGLTEXSUBIMAGE2DPROC)                   \
  X(Uniform1f, PFNGLUNIFORM1FPROC)                           \
  X(Uniform1i, PFNGLUNIFORM1IPROC)                           \
  X(Uniform2f, PFNGLUNIFORM2FPROC)                           \
  X(Uniform4f, PFNGLUNIFORM4FPROC)                           \
  X(UseProgram, PFNGLUSEPROGRAMPROC)                         \
  X(Viewport, PFNGLVIEWPORTPROC)

struct GlApi {
#define LUEUR_GL_MEMBER(name, type) type name = nullptr;
  LUEUR_GL_FUNCTIONS(LUEUR_GL_MEMBER)
#undef LUEUR_GL_MEMBER
};

/// Loads every function from the current context. Throws std::runtime_error naming the first one missing.
GlApi load_gl_api(GlGetProcAddress get_proc);

/// "renderer, version" of the current context, for messages.
std::string describe_gl_context(const GlApi& gl);

}  // namespace lueur
