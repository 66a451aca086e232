// Two scissored draws and a cleared column.
#include "display/split_view.h"

#include <algorithm>

#include "settings/compare.h"

namespace lueur {

void draw_split_view(const GlApi& gl, const DisplayPipeline& left, const Settings& left_shown,
                     const DisplayPipeline& right, const Settings& right_shown, const PixelRect& viewport,
                     const PixelRect& image) {
  const int column = split_column(left_shown.compare_split, image.width);
  left.draw(left_shown, viewport, image, PixelRect{image.x, image.y, column, image.height});
  right.draw(right_shown, viewport, image, PixelRect{image.x + column, image.y, image.width - column, image.height});
  // The divider: a light column centred on the split, inside the image.
  const int x = std::clamp(image.x + column - kDividerWidth / 2, image.x, image.x + image.width - kDividerWidth);
  gl.Enable(GL_SCISSOR_TEST);
  gl.Scissor(x, image.y, kDividerWidth, image.height);
  gl.ClearColor(0.9f, 0.9f, 0.9f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  gl.Disable(GL_SCISSOR_TEST);
}

}  // namespace lueur
