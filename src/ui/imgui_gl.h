// Dear ImGui's OpenGL 3 renderer on whatever context is current (GLFW window, EGL or OSMesa): its GL functions are
// loaded through that context's get-proc-address instead of the back-end's own dlopen of libGL.
#pragma once

#include "display/gl_api.h"

namespace lueur {

/// Loads the back-end's GL functions and initialises it (after ImGui::CreateContext). Throws std::runtime_error.
void init_imgui_opengl(GlGetProcAddress get_proc);
void shutdown_imgui_opengl();
/// Starts a renderer frame (call before ImGui::NewFrame) and draws ImGui's draw data into the bound framebuffer.
void imgui_opengl_new_frame();
void imgui_opengl_render();

}  // namespace lueur
