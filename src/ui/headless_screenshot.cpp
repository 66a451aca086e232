// One off-screen frame: context, display pipeline, optional ImGui panel, read-back.
#include "ui/headless_screenshot.h"

#include <imgui.h>

#include "display/offscreen_target.h"
#include "display/split_view.h"
#include "settings/compare.h"
#include "ui/imgui_gl.h"

namespace lueur {
namespace {

/// ImGui sizes auto-fitting windows over the first frames; the screenshot is the frame after they settle.
constexpr int kImguiSettleFrames = 3;

void draw_panel_offscreen(GlGetProcAddress get_proc, PanelModel& panel, int width, int height) {
  IMGUI_CHECKVERSION();
  ImGuiContext* context = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // a screenshot must not write imgui.ini into the working directory
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  try {
    init_imgui_opengl(get_proc);
    for (int frame = 0; frame < kImguiSettleFrames; ++frame) {
      imgui_opengl_new_frame();
      ImGui::NewFrame();
      draw_panel(panel);
      ImGui::Render();
    }
    imgui_opengl_render();
    shutdown_imgui_opengl();
  } catch (...) {
    ImGui::DestroyContext(context);
    throw;
  }
  ImGui::DestroyContext(context);
}

}  // namespace

Screenshot render_headless_screenshot(HeadlessGl kind, const Film& film, const Settings& shown, PanelModel* panel,
                                      const Film* right) {
  const HeadlessContext context = create_headless_context(kind);
  const GlApi gl = load_gl_api(context.get_proc);
  Screenshot shot;
  shot.width = film.width;
  shot.height = film.height;
  shot.context = context.kind + " (" + describe_gl_context(gl) + ")";
  {
    DisplayPipeline pipeline(gl);
    OffscreenTarget target(gl, film.width, film.height);
    pipeline.update(film, 1, shown);
    target.bind();
    const PixelRect full{0, 0, film.width, film.height};
    if (right) {
      const Settings right_shown = compared_settings(shown).value_or(shown);
      DisplayPipeline right_pipeline(gl);
      right_pipeline.update(*right, 1, right_shown);
      target.bind();
      draw_split_view(gl, pipeline, shown, right_pipeline, right_shown, full, full);
    } else {
      pipeline.draw(shown, full, full);
    }
    if (panel) draw_panel_offscreen(context.get_proc, *panel, film.width, film.height);
    shot.rgb = target.read_rgb8();
  }
  return shot;
}

}  // namespace lueur
