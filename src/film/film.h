// The film: one exact RGB sum per layer plus the frame count, and the image they average to.
// This folder, film/, holds the film and what reads it (averages, the noise estimate and its view, the pixel probe,
// tone mapping). The film accumulates pixels only: the L1 store the integrator learns lives beside it
// (store/l1_cache.h), not in it. Depends on core and passes.
//
// The sums are exact so that any split of the frames gives the same bytes: each sample is rounded to a multiple of
// the film's unit (2^-32 of the brightest emission) and summed as a 64-bit integer. Integer addition is associative,
// so frames added in any order, on any thread, rank or resumed run, give the same sums; float sums would depend on
// the order. The float sums that everything else reads are made from the exact ones after each frame.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/math.h"
#include "passes/render_settings.h"

namespace lueur {

/// A linear float RGB image, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< 3 x width x height
  Vec3 at(int x, int y) const {
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return Vec3(rgb[i], rgb[i + 1], rgb[i + 2]);
  }
};

/// The pass sums as they stood after `frames` frames (empty when the pass is not rendered or frames is 0).
struct PassSnapshot {
  uint64_t frames = 0;
  std::array<std::vector<float>, kPassCount> sums;
};

/// How many snapshots the film keeps for the noise estimate (film/noise_estimate.h): at the last four powers of
/// two of its frame count.
inline constexpr int kNoiseCheckpoints = 4;

/// Exact per-layer sums: counts of the film's unit, 3 x width x height per rendered layer.
using ExactSums = std::array<std::vector<int64_t>, kLayerCount>;

/// The largest sample, in units, that a film accepts (2^24 times the brightest emission): a larger one is dropped
/// and counted, so that 2^31 frames of samples as bright as the brightest emitter still fit in 64 bits.
inline constexpr double kMaxSampleUnits = 0x1p56;

/// What a film keeps besides its frame count; said once, when the film is made.
enum class FilmMode : int {
  /// The exact sums, the float sums made from them after each frame, and the noise snapshots: a render that is
  /// shown, written or resumed.
  kFull,
  /// The exact sums alone: an MPI rank's share of the frames, reduced into a kFull film on rank 0.
  kExactOnly,
  /// The float sums and snapshots alone, copied from a kFull film: what a tracer publishes to the display. It
  /// accumulates nothing itself.
  kShownCopy,
};

struct Film {
  Film() = default;
  explicit Film(FilmMode film_mode) : mode(film_mode) {}

  FilmMode mode = FilmMode::kFull;
  int width = 0, height = 0;
  /// The value of one count of `exact`: a power of two, 2^-32 of the brightest emission rounded up to a power of
  /// two (at least 1). 0 until the first frame chooses it (integrator/renderer.h: film_unit).
  double unit = 0.0;
  ExactSums exact;  ///< the sums, exact; empty when not rendered (and in a kShownCopy)
  std::array<std::vector<float>, kLayerCount> sums;  ///< exact x unit as floats, what the image is made from
  uint64_t frames = 0;
  /// The pass sums when the frame count was last a power of two N, then at N/2, N/4 and N/8 (frames 0: none yet).
  std::array<PassSnapshot, kNoiseCheckpoints> checkpoints;

  /// Sizes the buffers for the layers these settings need (those the mode keeps) and clears everything.
  void reset(int new_width, int new_height, const std::array<bool, kLayerCount>& layers);
  void reset(const RenderSettings& settings);
  size_t pixel_count() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  /// Whether the layer is rendered.
  bool has(Layer l) const {
    return mode == FilmMode::kShownCopy ? !sums[static_cast<size_t>(l)].empty() : !exact[static_cast<size_t>(l)].empty();
  }
  bool has(Pass p) const { return has(layer_of(p)); }
  /// Adds one frame's values (per layer, one Vec3 per pixel; a layer the film does not render is ignored) and counts
  /// the frame. A pixel sample with a value that is not finite or is larger than kMaxSampleUnits is dropped whole.
  /// Returns the number of pixel samples dropped.
  uint64_t add_frame(const std::array<std::vector<Vec3>, kLayerCount>& values);
  /// Adds the sums of frames rendered elsewhere (another film's `exact`, an MPI reduction) and sets the frame count
  /// to `frames_after`, as if they had been rendered here. Throws std::logic_error if that would pass a power of two
  /// of the frame count, at or above `snapshots_from`, without stopping at it (its noise snapshot would be missing).
  /// A render that knows its last frame needs no snapshot below the lowest of the last kNoiseCheckpoints powers of
  /// two (needed_snapshots_from). Throws std::overflow_error, adding nothing, if a sum would pass 64 bits (a part
  /// from a corrupt or hostile source).
  void add_exact(const ExactSums& part, uint64_t frames_after, uint64_t snapshots_from = 0);
  /// Remakes the float sums from the exact ones.
  void refresh_sums();
  /// Counts a frame whose values are in the exact sums: remakes the float sums and snapshots the pass sums when the
  /// count becomes a power of two.
  void finish_frame();
};

/// Whether n is a power of two (0 is not).
inline bool is_power_of_two(uint64_t n) { return n != 0 && (n & (n - 1)) == 0; }

/// The lowest power of two whose snapshot a film of `final_frames` frames still holds (the last kNoiseCheckpoints
/// powers of two up to it); 0 when every power is kept (fewer than 2^kNoiseCheckpoints frames).
inline uint64_t needed_snapshots_from(uint64_t final_frames) {
  uint64_t highest = 1;
  while (highest <= final_frames / 2) highest <<= 1;
  return final_frames == 0 ? 0 : highest >> (kNoiseCheckpoints - 1);
}

/// The running average of one layer (black if the layer has no samples).
Image layer_average(const Film& film, Layer layer);
inline Image pass_average(const Film& film, Pass pass) { return layer_average(film, layer_of(pass)); }

/// sum over enabled passes of weight x average(pass).
Image combine_passes(const Film& film, const std::array<bool, kPassCount>& enabled,
                     const std::array<float, kPassCount>& weights);

/// What a display shows of the film: the average of `layer` when one is chosen, else the weighted combination.
inline Image shown_image(const Film& film, const std::array<bool, kPassCount>& enabled,
                         const std::array<float, kPassCount>& weights, const std::optional<Layer>& layer) {
  return layer ? layer_average(film, *layer) : combine_passes(film, enabled, weights);
}

}  // namespace lueur
