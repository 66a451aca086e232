// How much memory rendering and saving an image takes, so that a size the machine cannot hold is refused before
// anything is allocated. Depends on the render settings and buffers.
#pragma once

#include "passes/render_settings.h"

#include <cstdint>

namespace lueur {

/// Peak bytes of a render at these settings: the film, plus the larger of one frame's buffers and the images
/// made when saving (the EXR encoder holds every layer several times over), plus a fixed allowance for the
/// process. The scene is not included; the loader budgets for it.
uint64_t render_memory_bytes(const RenderSettings& settings);

}  // namespace lueur
