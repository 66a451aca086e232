// The headless mode: render N frames of a scene and write one image file.
#pragma once

#include "app/options.h"

namespace lueur {

/// Renders and writes `options.out_path`. Returns the process exit status: 0, 2 after printing an error, or 128 + the
/// signal when SIGINT or SIGTERM stopped it early (the frames done are written all the same).
int run_headless(const AppOptions& options);

}  // namespace lueur
