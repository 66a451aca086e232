// The GLFW window around the viewer's loop: an OpenGL 3.3 core context, the callbacks that collect input between
// frames (InputEvents), and Dear ImGui's GLFW and OpenGL 3 back-ends.
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <stdexcept>

#include "app/viewer.h"
#include "app/viewer_state.h"
#include "ui/imgui_gl.h"

namespace lueur {

InputEvents& events_of(GLFWwindow* window) { return *static_cast<InputEvents*>(glfwGetWindowUserPointer(window)); }

namespace {

GlProc glfw_get_proc(const char* name) { return reinterpret_cast<GlProc>(glfwGetProcAddress(name)); }

/// Installed before ImGui's back-end, which chains to them.
void install_callbacks(GLFWwindow* window) {
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) { events_of(w).scroll += y; });
  // The cursor as the events move it, in their order: a press is recorded where the cursor was when it happened,
  // not where it is when the frame that delivers it begins.
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    InputEvents& events = events_of(w);
    events.cursor_x = x;
    events.cursor_y = y;
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    InputEvents& events = events_of(w);
    events.buttons.record(button, action == GLFW_PRESS, events.cursor_x, events.cursor_y);
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (key == GLFW_KEY_TAB && action == GLFW_PRESS) ++events_of(w).tab_presses;
  });
  glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
    for (int i = 0; i < count; ++i) events_of(w).dropped.emplace_back(paths[i]);
  });
}

}  // namespace

int run_viewer(const AppOptions& options) {
  if (!glfwInit())
    throw std::runtime_error("cannot open a window (no display?): render to a file with --headless --out FILE");
  struct GlfwTerminate {
    ~GlfwTerminate() { glfwTerminate(); }
  } terminate;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // Wide enough for the image at its size beside the panel.
  GLFWwindow* window = glfwCreateWindow(window_width_for_image(options.settings.render.width, kPanelWidth),
                                        options.settings.render.height, "Lueur", nullptr, nullptr);
  if (!window) throw std::runtime_error("cannot create an OpenGL 3.3 core window");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);

  InputEvents events;
  glfwGetCursorPos(window, &events.cursor_x, &events.cursor_y);
  glfwSetWindowUserPointer(window, &events);
  install_callbacks(window);

  const GlApi gl = load_gl_api(glfw_get_proc);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the panel's layout is Lueur's, not a file in the working directory
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  init_imgui_opengl(glfw_get_proc);
  {
    Viewer viewer(options, window, gl);
    viewer.run();
  }
  shutdown_imgui_opengl();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  return 0;
}

}  // namespace lueur
