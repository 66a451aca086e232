// One off-screen frame: context, display pipeline, optional ImGui panel, read-back.
#include "ui/headless_screenshot.h"

#include <imgui.h>

#include "display/offscreen_target.h"
#include "display/split_view.h"
#include "display/window_layout.h"
#include "settings/compare.h"
#include "ui/imgui_gl.h"

namespace lueur {
namespace {

/// ImGui sizes auto-fitting windows over the first frames; the screenshot is the frame after they settle.
constexpr int kImguiSettleFrames = 3;

void draw_panel_offscreen(GlGetProcAddress get_proc, PanelModel& panel, int width, int height, bool over_image) {
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
      draw_panel(panel, static_cast<float>(height), over_image);
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
  // With the panel, the screenshot is laid out as the window is: the panel's column, the image beside it.
  const double panel_width = panel ? panel->panel_width : 0.0;
  shot.width = window_width_for_image(film.width, panel_width);
  shot.height = film.height;
  shot.context = context.kind + " (" + describe_gl_context(gl) + ")";
  {
    DisplayPipeline pipeline(gl);
    OffscreenTarget target(gl, shot.width, shot.height);
    pipeline.update(film, 1, shown);
    target.bind();
    const WindowLayout layout = lay_out_window(shot.width, shot.height, shot.width, shot.height, panel_width);
    const PixelRect full{0, 0, shot.width, shot.height};
    const PixelRect& image = layout.image_pixels;
    if (right) {
      const Settings right_shown = compared_settings(shown).value_or(shown);
      DisplayPipeline right_pipeline(gl);
      right_pipeline.update(*right, 1, right_shown);
      target.bind();
      draw_split_view(gl, pipeline, shown, right_pipeline, right_shown, full, image);
    } else {
      pipeline.draw(shown, full, image);
    }
    if (panel) draw_panel_offscreen(context.get_proc, *panel, shot.width, shot.height, layout.panel_over_image);
    shot.rgb = target.read_rgb8();
  }
  return shot;
}

}  // namespace lueur
