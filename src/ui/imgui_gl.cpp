// The implementation half of the back-end's gl3w-style loader header lives here; the back-end itself is compiled
// from Debian's source with IMGUI_IMPL_OPENGL_LOADER_CUSTOM (see third_party/dependencies.cmake).
#include "ui/imgui_gl.h"

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#define IMGL3W_IMPL
#include <imgui_impl_opengl3_loader.h>

#include <stdexcept>

namespace lueur {

void init_imgui_opengl(GlGetProcAddress get_proc) {
  if (imgl3wInit2(reinterpret_cast<GL3WGetProcAddressProc>(get_proc)) != 0)
    throw std::runtime_error("Dear ImGui: cannot load OpenGL 3 functions from the current context");
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw std::runtime_error("Dear ImGui: the OpenGL 3 renderer failed to initialise");
}

void shutdown_imgui_opengl() { ImGui_ImplOpenGL3_Shutdown(); }
void imgui_opengl_new_frame() { ImGui_ImplOpenGL3_NewFrame(); }
void imgui_opengl_render() { ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData()); }

}  // namespace lueur
