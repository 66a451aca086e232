// What the tracer renders: passes, light sampling, ray counts, reuse, seed. Plain data with name tables that serve
// both the command line and the UI. Depends on core and passes.h.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/math.h"
#include "core/pixel_sampler.h"
#include "passes/passes.h"

namespace lueur {

/// How L1 picks the emitter a shadow ray goes to.
/// `importance`: by a bound on what each emitter can send to the shaded point (lights/light_clusters.h).
enum class LightStrategy : int { kAll = 0, kUniform = 1, kArea = 2, kPower = 3, kImportance = 4 };
inline constexpr std::array<std::string_view, 5> kLightStrategyNames = {"all", "uniform", "area", "power",
                                                                        "importance"};

/// Where L2 takes L1(q) from when a bounce ray hits q: nowhere (recompute), the screen (the report's reuse: this
/// frame's pixels or their running average), the world-space L1 store (the report's improvement II-B), or both: the
/// store where its cell is ready, the screen where it is not and the camera saw q, recomputation otherwise (the
/// screen only while the store is young: integrator/renderer.h, kScreenCacheFrames).
enum class ReuseMode : int { kOff = 0, kFrame = 1, kAverage = 2, kCache = 3, kScreenCache = 4 };
inline constexpr std::array<std::string_view, 5> kReuseModeNames = {"off", "frame", "average", "cache", "screen+cache"};
inline constexpr bool uses_screen(ReuseMode m) {
  return m == ReuseMode::kFrame || m == ReuseMode::kAverage || m == ReuseMode::kScreenCache;
}
inline constexpr bool uses_cache(ReuseMode m) { return m == ReuseMode::kCache || m == ReuseMode::kScreenCache; }

/// Everything that changes the rendered estimate. Changing any of it restarts the accumulation.
struct RenderSettings {
  int width = 512;
  int height = 512;
  std::array<bool, kPassCount> enabled = {true, true, true, false, false};
  LightStrategy lights = LightStrategy::kImportance;
  int le_rays = 4;       ///< camera rays per pixel per frame that estimate Le (1: the ray that carries L1, L2, AO)
  int l1_rays = 16;      ///< shadow rays per pixel per frame
  float blinn_k = 0.7f;  ///< the report's Lambert share for materials without Ks
  int l2_rays = 16;      ///< cosine-weighted bounce rays per pixel per frame
  ReuseMode reuse = ReuseMode::kFrame;
  float recompute_ratio = 0.125f;   ///< L1(q) is recomputed with this share of l1_rays (at least one ray)
  bool reuse_diffuse_only = false;  ///< reuse only the view-independent part of L1; recompute the rest
  bool camera_light = false;  ///< the head-light (camera_light.h) lights what the camera sees, besides the emitters
  float cache_cell_pixels = 0.0f;  ///< the L1 store's cells span about this many pixels at first (then shrink);
                                   ///< 0 or less: automatic (cache_cell_pixels_in_use)
  int cache_mb = 256;              ///< the L1 store's memory cap, in MiB
  int ao_rays = 16;
  int ln_rays = 8;  ///< paths per pixel per frame that carry the light of the second and later bounces (ln)
  /// Scattering events a path may have, counted as Cycles counts them: every diffuse, glossy, mirror or glass
  /// bounce, the camera's specular ones included. 1 is Le + L1 + L2 (ln then carries nothing).
  int max_bounces = 8;
  float ao_radius = 0.0f;  ///< world units; 0 or less: a tenth of the scene's bounding-box diagonal
  uint64_t seed = 0;
  SamplerKind sampler = SamplerKind::kSobol;  ///< where the estimators' random numbers come from

  bool operator==(const RenderSettings&) const = default;
  bool pass_enabled(Pass p) const { return enabled[static_cast<size_t>(p)]; }
  /// Shadow rays for a recomputed L1(q).
  int recompute_rays() const {
    return std::max(1, static_cast<int>(std::lround(recompute_ratio * static_cast<float>(l1_rays))));
  }
  /// The L1 store's cell size in pixels: cache_cell_pixels, or where that is 0 the automatic size.
  float cache_cell_pixels_in_use() const {
    return cache_cell_pixels > 0.0f ? cache_cell_pixels : automatic_cache_cell_pixels();
  }
  /// The automatic cell size: 2 x sqrt(height / 128) pixels (2 at 128 lines, 4 at 512). Why the square root: a
  /// cell's blur is its size in the world, which falls as 1 / height for a given number of pixels, while what it
  /// costs to fill, per sample the frame gathers, does not depend on the height; the sum of a squared bias
  /// ~ (c / height)^2 and a cost ~ 1 / c^2 is least at c ~ sqrt(height). Measured (`screen+cache`, L2 against long
  /// `off` renders): 2 pixels best at 128x128 on both benchmark scenes, 2.83 the only size that kept the conference
  /// room's image ahead of `frame`'s at 256x256, and 4 or 8 better than 2 at 512x512 on the default scene
  /// (BENCHMARKS.md).
  float automatic_cache_cell_pixels() const {
    return 2.0f * std::sqrt(static_cast<float>(std::max(height, 1)) / 128.0f);
  }
};

/// The film layers a frame must fill for these settings: the enabled passes, L1 also when L2 reuses its running
/// average, and the reuse layers whenever L2 runs.
std::array<bool, kLayerCount> layers_needed(const RenderSettings& settings);

}  // namespace lueur
