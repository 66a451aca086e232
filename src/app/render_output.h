// What every headless render shares, in one process (app/headless.cpp) or across MPI ranks (src/mpi/): checking the
// output and the memory before the work, the header line, writing the image and the resume state, resuming, and the
// summary at the end.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/options.h"
#include "app/scene_source.h"
#include "core/memory_budget.h"
#include "film/film.h"
#include "runtime/resume_state.h"
#include "integrator/renderer.h"
#include "integrator/traced_scene.h"
#include "ui/panel.h"

namespace lueur {

/// What frames cost and found, added up. Plain numbers only: lueur-mpi gathers it from every rank.
struct FrameTally {
  uint64_t rays = 0, bounce_hits = 0, reused = 0, cached = 0, dropped = 0;
  uint64_t ln_lookups = 0, ln_reused = 0, ln_cached = 0, ln_paths = 0, ln_ended = 0;
  ServedSamples served;
  double l2_seconds = 0.0;
  double left_seconds = 0.0, right_seconds = 0.0;  ///< an A/B split's tracing time per side
  void add(const FrameTally& other);
};

/// What a render did, for the summary and a --ui screenshot's panel.
struct RunFigures {
  double seconds = 0.0;
  FrameTally tally;
  L1CacheStats cache;
  std::vector<NoisePoint> noise_history;  ///< the estimate at each power of two of the frames (for --ui)
};

/// Renders the next frame of `left` and, for an A/B split, of `right` (rendered with `right_settings`), timing each
/// side, and adds what they cost to `tally`. Returns the left side's result.
FrameResult render_frame_pair(const TracedScene& traced, const Camera& camera, const RenderSettings& left_settings,
                              Accumulation& left, const RenderSettings* right_settings, Accumulation* right,
                              ThreadPool& pool, FrameTally& tally);

/// A render about to start: the scene opened, the camera, the film and L1 store (and, for an A/B split, the right
/// side's settings, film and store), each checked against the settings.
struct RenderJob {
  OpenedScene opened;
  Camera camera;
  Accumulation left;
  std::optional<Settings> right;  ///< --compare: the settings of the split's right side
  Accumulation right_side;
  double load_seconds = 0.0;  ///< reading the scene and building its accelerator (open_scene)
  std::vector<Accumulation*> sides() {
    return right ? std::vector<Accumulation*>{&left, &right_side} : std::vector<Accumulation*>{&left};
  }
  Film* right_film() { return right ? &right_side.film : nullptr; }
};

/// Checks the output path (unless `writes_output` is false: an MPI rank other than 0) and the memory, opens the
/// scene (printing its warnings and notes if `writes_output`), and sizes the films. Throws UsageError, IoError or
/// SceneError with one line.
RenderJob prepare_render_job(const AppOptions& options, bool writes_output = true);

/// Refuses an output that could never be written before spending minutes rendering it. Throws IoError.
void check_output_path(const std::string& path);

/// The part of that check that holds for any file Lueur writes: not a directory, in a directory that exists and is
/// writable. Throws IoError ("cannot write 'PATH': ...").
void check_writable_path(const std::string& path);

/// Refuses a render of `frames` frames that would pass the frames these settings can take before their sample
/// sequences start over (frames_before_samples_repeat). `side` names an A/B split's side in the message. Throws
/// UsageError.
void refuse_repeating_samples(const RenderSettings& settings, int frames, const std::string& side);

/// Refuses an image whose buffers the machine cannot hold, before anything is loaded or allocated; returns what
/// is left of the budget for the scene. Throws UsageError.
MemoryBudget reserve_render_memory(const RenderSettings& settings, const RenderSettings* right);

/// The header line: scene, triangles, emitters, textures, size, frames, who renders (`workers`), back-end, and the
/// seconds the scene took to read and prepare.
void print_render_header(const AppOptions& options, const RenderJob& job, const std::string& workers);

/// Appends the estimate at this power of two of the frames to `figures.noise_history` (only for a --ui screenshot).
void record_noise_history(const AppOptions& options, const Film& film, double elapsed, RunFigures& figures);

/// Writes the image of `film` (and `right`, for an A/B split) after `frames_done` frames, atomically: a PNG through
/// the GL display path or the CPU, a PFM, or an EXR of every layer. Throws IoError.
void write_render_output(const AppOptions& options, const Film& film, const Film* right, const TracedScene& traced,
                         const RunFigures& figures);

/// Where --checkpoint writes the resume state: beside the image, as OUT.lueur-state.
std::string state_path_of(const std::string& out_path);

/// The settings and scene that the resume state must match: every setting that changes the estimate (the table's
/// restart and reload rows), the scene's path and size. Display settings and frame counts may change.
RenderIdentity render_identity(const AppOptions& options, const TracedScene& traced);

/// Writes the image so far and the resume state beside it (each side's film and L1 store), each atomically.
void write_checkpoint(const AppOptions& options, const Accumulation& left, const Accumulation* right,
                      const TracedScene& traced, const RunFigures& figures);

/// The end of a render: says why it stopped before its last frame, if it did (the time limit, the target noise, or
/// `interrupted_by`, the signal that cut it short, 0 for none), and writes the image (and, with --checkpoint, the
/// resume state). Throws IoError.
void finish_render(const AppOptions& options, const Accumulation& left, const Accumulation* right,
                   const TracedScene& traced, const RunFigures& figures, bool out_of_time, bool stopped_by_noise,
                   int interrupted_by = 0);

/// Restores the films and L1 stores from --resume. Throws UsageError naming the file and the problem.
void resume_render(const AppOptions& options, const TracedScene& traced, const std::vector<Accumulation*>& sides);

/// The lines printed after a render: frames and rays, L2's reuse, the L1 store, each side of an A/B split, and the
/// noise estimate of every pass and, last, of the image.
void print_run_summary(const AppOptions& options, const Film& film, const Film* right, const RunFigures& figures);

}  // namespace lueur
