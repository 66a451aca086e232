// The L1 store against screen-space reuse (issue 19): on the default scene and the conference room (camera inside),
// each reuse mode renders for the same time, its L2 and image error against a long `--reuse off` reference are
// followed frame by frame, and the time each mode takes to reach the L2 error that `frame` reaches at the end is
// read off those curves. Depends on the renderer and the benchmark scenes.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "bench/bench_scenes.h"

namespace lueur::bench {

struct StoreOptions {
  int size = 256;                    ///< square images
  double seconds = 60.0;             ///< the equal time each mode gets
  double reference_seconds = 240.0;  ///< the reference (`off`, another seed) renders at least this long
  double turn_seconds = 2.0;         ///< the modes take turns of this long (each on its own frames' clock)
  int threads = 0;                   ///< 0: all
  float cell_pixels = 0.0f;          ///< the store modes' --cache-cell-pixels (0: automatic, the renderer's default)
  /// The conference room's light: the benchmark's own small ceiling light (false), or the panel of Lueur's default
  /// light rig, as `lueur conference.obj` lights the room (true). The camera is the benchmark's either way.
  bool conference_rig = false;
};

/// One JSON object per scene and mode. Progress goes to `log`.
nlohmann::ordered_json run_store_comparison(std::vector<BenchScene>& scenes, const StoreOptions& options,
                                            std::FILE* log);

}  // namespace lueur::bench
