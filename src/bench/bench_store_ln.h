// ln with and without the L1 store (issue 51): on the conference room seen from inside and on CornellBox-Original,
// every light pass on at 8 bounces, `--reuse off` renders for a fixed time and the store modes take turns with it;
// ln's error against an unbiased reference (two `off` renders of their own seeds, their noise taken out as in
// bench_store_frames.h) is followed frame by frame, and the time each store mode takes to reach `off`'s final ln
// error is read off its curve. Depends on the renderer and the benchmark scenes.
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_scenes.h"

namespace lueur::bench {

struct StoreLnOptions {
  int size = 64;                     ///< square images
  double seconds = 60.0;             ///< `off`'s time; the store modes render as long
  double reference_seconds = 120.0;  ///< each of the two references renders at least this long
  double turn_seconds = 2.0;         ///< the modes take turns of this long, each on its own frames' clock
  int threads = 0;                   ///< 0: all
};

/// One JSON object per scene and mode. Progress goes to `log`.
nlohmann::ordered_json run_store_ln(std::vector<BenchScene>& scenes, const StoreLnOptions& options, std::FILE* log);

}  // namespace lueur::bench
