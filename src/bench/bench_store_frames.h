// The L1 store's error as frames accumulate (issue 51): on the default scene, the conference room seen from inside
// and a closed room seen from inside facing a wall, each reuse mode renders L2 alone for a fixed number of frames,
// and its L2 error against an unbiased `--reuse off` reference is read at every power of two of frames. The
// reference is two `off` renders with other seeds; their own noise (a quarter of their squared difference) is
// subtracted from every error, so that the figures are the modes' own error. Depends on the renderer and the
// benchmark scenes.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_scenes.h"
#include "passes/render_settings.h"

namespace lueur::bench {

struct StoreFramesOptions {
  int size = 64;           ///< square images
  uint64_t frames = 4096;  ///< each mode's frames; errors at 64, 128, ... up to this
  uint64_t first_checkpoint = 64;
  uint64_t reference_frames = 8192;  ///< frames of each of the two `off` references
  int threads = 0;                   ///< 0: all
  /// Where the references are kept between runs (PFM, named by scene, size and frames); empty: not kept. Only
  /// `off` renders them, so a change to the store leaves them valid.
  std::string reference_dir;
  /// The reuse modes measured (the default: off, frame, cache, screen+cache).
  std::vector<ReuseMode> modes = {ReuseMode::kOff, ReuseMode::kFrame, ReuseMode::kCache, ReuseMode::kScreenCache};
};

/// One JSON object per scene and mode. Progress goes to `log`.
nlohmann::ordered_json run_store_frames(std::vector<BenchScene>& scenes, const StoreFramesOptions& options,
                                        std::FILE* log);

}  // namespace lueur::bench
