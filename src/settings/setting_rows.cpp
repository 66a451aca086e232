// The table of settings itself: one row per member of Settings. A new setting is one row here (plus its widget in
// the panel, where it has one). The rows' order is that of the command line's help and of the settings written
// into images (kept from before the table existed, so that images stay byte for byte the same).
#include <limits>
#include <string>

#include "store/l1_cache.h"
#include "settings/setting_kinds.h"

namespace lueur::setting_rows {
namespace {

std::vector<Row> make_rows() {
  using E = SettingEffect;
  const SettingRange rays{0, 4096}, ray_slider{0, 64};
  const double u64_max = static_cast<double>(std::numeric_limits<uint64_t>::max());
  std::vector<Row> table;
  table.push_back(size_row());
  Row frames = integer_row("frames", "frames a headless render accumulates", E::kNone,
                           [](auto& s) -> auto& { return s.frames; }, {1, 1e6});
  // A view saved before its first frame holds 0 frames: it keeps the default instead of being refused.
  frames.read_json = [read = frames.read_json](const nlohmann::json& root, Settings& s) {
    const auto it = root.find("frames");
    if (it != root.end() && it->is_number_integer() && it->get<int64_t>() == 0) return;
    read(root, s);
  };
  table.push_back(frames);
  table.push_back(passes_row());
  table.push_back(weights_row());
  table.push_back(enum_row<LightStrategy>(
      "lights",
      "how L1 picks the emitter of each shadow ray: a point on every one (all), one uniformly, by area (the "
      "report's), by area x brightness (power), or by what each can send to the shaded point (importance)",
      E::kRestart, kLightStrategyNames, [](auto& s) -> auto& { return s.render.lights; }));
  table.push_back(integer_row(
      "le-rays",
      "camera rays per pixel per frame that see Le (emission), anti-aliasing the emitters' edges: with 1, the "
      "pixel's ray that also carries L1, L2 and AO; with more, rays of their own",
      E::kRestart, [](auto& s) -> auto& { return s.render.le_rays; }, SettingRange{1, 4096}, SettingRange{1, 64}));
  table.push_back(integer_row(
      "l1-rays", "L1 shadow rays per pixel per frame", E::kRestart, [](auto& s) -> auto& { return s.render.l1_rays; },
      rays, ray_slider));
  table.push_back(integer_row(
      "l2-rays", "L2 bounce rays per pixel per frame", E::kRestart, [](auto& s) -> auto& { return s.render.l2_rays; },
      rays, ray_slider));
  table.push_back(enum_row<ReuseMode>(
      "reuse",
      "where L2 takes L1 at a bounce hit from: nowhere (recompute), this frame's pixels, their running average, the "
      "world-space L1 store, or the store where its cell is ready and the screen where not",
      E::kRestart, kReuseModeNames, [](auto& s) -> auto& { return s.render.reuse; }));
  // The store's fill is a constant of the store (store/l1_cache.h): the text is built from it, never restated.
  static const std::string recompute_help =
      "share of the L1 rays that recompute L1 where it cannot be reused (the store modes recompute with " +
      std::to_string(kL1CacheFillRays) + " shadow rays, which fill the store's cell, where the store has room for it)";
  table.push_back(real_row(
      "recompute-ratio", recompute_help, E::kRestart, [](auto& s) -> auto& { return s.render.recompute_ratio; },
      {0, 16}, SettingRange{0, 1}));
  table.push_back(switch_row(
      "reuse-diffuse-only", "reuse only the view-independent part of L1 (no bias on glossy surfaces)", E::kRestart,
      [](auto& s) -> auto& { return s.render.reuse_diffuse_only; }, true));
  Row cache_cells = real_row(
      "cache-cell-pixels",
      "the L1 store's cell size in pixels at the cell's distance, for the first 4 frames (halved per 8x frames); 0: "
      "automatic, 2 x sqrt(image height / 128) (2 at 128 lines, 4 at 512)",
      E::kRestart, [](auto& s) -> auto& { return s.render.cache_cell_pixels; }, {0, 1024}, SettingRange{1, 32});
  cache_cells.always_described = false;
  table.push_back(cache_cells);
  Row cache_mb = integer_row(
      "cache-mb", "the L1 store's memory cap in MiB (full: it stops taking new cells)", E::kRestart,
      [](auto& s) -> auto& { return s.render.cache_mb; }, {1, 1 << 20}, SettingRange{16, 4096});
  cache_mb.always_described = false;
  table.push_back(cache_mb);
  table.push_back(integer_row(
      "ao-rays", "AO rays per pixel per frame", E::kRestart, [](auto& s) -> auto& { return s.render.ao_rays; }, rays,
      ray_slider));
  Row ao_radius = real_row("ao-radius", "AO radius in world units; 0: a tenth of the scene's diagonal", E::kRestart,
                           [](auto& s) -> auto& { return s.render.ao_radius; }, {0, 1e30});
  ao_radius.always_described = false;
  table.push_back(ao_radius);
  // Written into images and the settings text only where they differ from their defaults: an image of the report's
  // passes reads as it did before the further bounces came.
  Row ln_rays = integer_row(
      "ln-rays",
      "paths per pixel per frame that carry ln, the light of the second and later bounces (next-event estimation "
      "and multiple importance sampling at every vertex, Russian roulette after the first few)",
      E::kRestart, [](auto& s) -> auto& { return s.render.ln_rays; }, rays, SettingRange{1, 64});
  ln_rays.always_described = false;
  table.push_back(ln_rays);
  Row max_bounces = integer_row(
      "max-bounces",
      "scattering events a path may have, counted as Cycles counts them (every diffuse, glossy, mirror or glass "
      "bounce, the camera's through mirrors and glass included): 1 is Le + L1 + L2",
      E::kRestart, [](auto& s) -> auto& { return s.render.max_bounces; }, SettingRange{1, 1024},
      SettingRange{1, 32});
  max_bounces.always_described = false;
  table.push_back(max_bounces);
  table.push_back(view_row());
  Row accel = enum_row<AccelKind>(
      "accel", "acceleration structure: Lueur's own BVH or Embree", E::kReload, kAccelKindNames,
      [](auto& s) -> auto& { return s.accel; });
  accel.always_described = false;
  table.push_back(accel);
  table.push_back(real_row(
      "blinn-k", "Lambert share K of the report's Blinn-Phong mix (materials without Ks)", E::kRestart,
      [](auto& s) -> auto& { return s.render.blinn_k; }, {0, 1}, SettingRange{0, 1}));
  table.push_back(switch_row(
      "smooth-normals", "smooth normals for files that have none", E::kReload,
      [](auto& s) -> auto& { return s.smooth_normals; }, false));
  table.push_back(switch_row(
      "light-rig", "light scenes without emitters with the default rig (a sky; in a closed room, a ceiling panel)",
      E::kReload, [](auto& s) -> auto& { return s.light_rig; }, false));
  table.push_back(switch_row(
      "camera-light",
      "a head-light: a small light just behind the camera, facing where it looks, lighting what it sees besides "
      "the scene's emitters (it moves with the camera; no ray sees it)",
      E::kRestart, [](auto& s) -> auto& { return s.render.camera_light; }, false));
  Row rig_scale = real_row(
      "light-rig-scale", "the default light rig's radiance factor", E::kReload,
      [](auto& s) -> auto& { return s.light_rig_scale; }, {0, 1e6}, SettingRange{0, 4});
  rig_scale.always_described = false;
  table.push_back(rig_scale);
  Row start_view = enum_row<StartView>(
      "start-view",
      "where a scene's camera starts: auto (inside a closed room, else outside framing the model), inside, outside; "
      "--camera inside and --camera outside say the same",
      E::kRestart, kStartViewNames, [](auto& s) -> auto& { return s.start_view; });
  start_view.always_described = false;
  table.push_back(start_view);
  table.push_back(
      integer_row("seed", "random seed", E::kRestart, [](auto& s) -> auto& { return s.render.seed; }, {0, u64_max}));
  table.push_back(enum_row<SamplerKind>(
      "sampler",
      "where the estimators' random numbers come from: independent streams, or "
      "Owen-scrambled Sobol points, one progressive sequence per pixel",
      E::kRestart, kSamplerKindNames, [](auto& s) -> auto& { return s.render.sampler; }));
  table.push_back(real_row(
      "exposure", "exposure in stops", E::kDisplay, [](auto& s) -> auto& { return s.display.exposure; }, {-30, 30},
      SettingRange{-10, 10}));
  table.push_back(enum_row<ToneMap>(
      "tonemap", "tone map", E::kDisplay, kToneMapNames, [](auto& s) -> auto& { return s.display.tonemap; }));
  table.push_back(camera_row());
  table.push_back(up_row());
  Row frame_limit = integer_row("frame-limit", "window: stop accumulating after this many frames (0: never)", E::kNone,
                                [](auto& s) -> auto& { return s.frame_limit; }, {0, u64_max});
  frame_limit.always_described = false;
  table.push_back(frame_limit);
  Row time_limit = real_row("time-limit",
                            "stop after this many seconds of tracing, once the frame in flight is done (0: never); the "
                            "image then depends on the machine's speed",
                            E::kNone, [](auto& s) -> auto& { return s.time_limit; }, {0, 1e9});
  time_limit.always_described = false;
  table.push_back(time_limit);
  Row target_noise = real_row("target-noise",
                              "stop once the image's estimated relMSE falls below this, once the frame in flight is "
                              "done (0: never); the image then depends on the noise estimate's history",
                              E::kNone, [](auto& s) -> auto& { return s.target_noise; }, {0, 1e9});
  target_noise.always_described = false;
  table.push_back(target_noise);
  Row watch = switch_row("watch",
                         "window: reload the scene when its OBJ, MTL or texture files change on disk (the camera "
                         "stays)",
                         E::kNone, [](auto& s) -> auto& { return s.watch; }, false);
  watch.always_described = false;
  table.push_back(watch);
  table.push_back(compare_row());
  Row compare_split =
      real_row("compare-split", "where the A/B split's divider stands, as a share of the width from the left",
               E::kDisplay, [](auto& s) -> auto& { return s.compare_split; }, {0, 1});
  compare_split.always_described = false;
  table.push_back(compare_split);

  for (Row& row : table) {
    if (!row.same)
      row.same = [format = row.format](const Settings& a, const Settings& b) { return format(a) == format(b); };
    row.info.default_text = row.format(Settings{}).value_or("");
  }
  return table;
}

}  // namespace

const std::vector<Row>& rows() {
  static const std::vector<Row> table = make_rows();
  return table;
}

}  // namespace lueur::setting_rows
