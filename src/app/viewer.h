// The interactive window: GLFW + OpenGL 3.3 core, the tracer thread behind it, the display shaders in front,
// and the ImGui panel on top.
#pragma once

#include "app/options.h"

namespace lueur {

/// Opens the window on the scene the options name and runs until it is closed. Throws for a window that cannot
/// be opened (no display); scene and file errors after that appear in the panel.
int run_viewer(const AppOptions& options);

}  // namespace lueur
