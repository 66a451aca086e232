// The A/B split view on the GPU: the left film drawn left of the divider, the right film right of it, and the
// divider itself, into whatever framebuffer is bound.
#pragma once

#include "display/display_pipeline.h"

namespace lueur {

/// Draws `left` (shown as `left_shown`) and `right` (as `right_shown`) into `image` of `viewport`, split at the
/// column `split_column(left_shown.compare_split, image.width)` of the image, with a divider line there.
void draw_split_view(const GlApi& gl, const DisplayPipeline& left, const Settings& left_shown,
                     const DisplayPipeline& right, const Settings& right_shown, const PixelRect& viewport,
                     const PixelRect& image);

/// The divider's width in framebuffer pixels.
inline constexpr int kDividerWidth = 2;

}  // namespace lueur
