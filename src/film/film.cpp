// Averages and the weighted combination of the per-pass sums.
#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lueur {

void Film::reset(int new_width, int new_height, const std::array<bool, kLayerCount>& layers) {
  if (mode == FilmMode::kShownCopy) throw std::logic_error("Film::reset: a shown copy accumulates nothing");
  width = new_width;
  height = new_height;
  frames = 0;
  unit = 0.0;
  for (size_t l = 0; l < kLayerCount; ++l) {
    if (layers[l]) {
      exact[l].assign(3 * pixel_count(), 0);
      if (mode == FilmMode::kFull) sums[l].assign(3 * pixel_count(), 0.0f);
    } else {
      exact[l].clear();
      sums[l].clear();
    }
  }
  for (PassSnapshot& checkpoint : checkpoints) {
    checkpoint.frames = 0;
    for (auto& pass : checkpoint.sums) pass.clear();
  }
}

uint64_t Film::add_frame(const std::array<std::vector<Vec3>, kLayerCount>& values) {
  if (mode == FilmMode::kShownCopy) throw std::logic_error("Film::add_frame: a shown copy accumulates nothing");
  uint64_t dropped = 0;
  const double inverse_unit = 1.0 / unit;  // exact: the unit is a power of two
  for (size_t l = 0; l < kLayerCount; ++l) {
    const std::vector<Vec3>& layer = values[l];
    if (layer.empty() || exact[l].empty()) continue;
    int64_t* sum = exact[l].data();
    for (size_t i = 0; i < layer.size(); ++i) {
      int64_t added[3];
      bool fits = true;
      for (int c = 0; c < 3; ++c) {
        const double scaled = static_cast<double>(layer[i][c]) * inverse_unit;
        // Also false for NaN. One extreme sample (a near-singular light path in a scene of extreme scale) must not
        // spoil a pixel for good: it is dropped and counted instead.
        fits = fits && std::fabs(scaled) <= kMaxSampleUnits &&
               !__builtin_add_overflow(sum[3 * i + c], std::llrint(scaled), &added[c]);
      }
      if (!fits) {
        ++dropped;
        continue;
      }
      for (int c = 0; c < 3; ++c) sum[3 * i + c] = added[c];
    }
  }
  finish_frame();
  return dropped;
}

void Film::add_exact(const ExactSums& part, uint64_t frames_after, uint64_t snapshots_from) {
  if (mode == FilmMode::kShownCopy) throw std::logic_error("Film::add_exact: a shown copy accumulates nothing");
  if (frames_after < frames) throw std::logic_error("Film::add_exact: the frame count cannot go down");
  if (frames_after == frames) return;
  // No power of two above the current count (and from `snapshots_from` on) may be skipped.
  uint64_t next_power = 1;
  while (next_power <= frames || next_power < snapshots_from) next_power <<= 1;
  if (frames_after > next_power) throw std::logic_error("Film::add_exact: a power of two of the frames was skipped");
  // Checked whole before anything is added, so that a refused part leaves the film as it was.
  for (size_t l = 0; l < kLayerCount; ++l) {
    if (exact[l].empty()) continue;
    if (part[l].size() != exact[l].size()) throw std::logic_error("Film::add_exact: the layers differ");
    int64_t sum = 0;
    for (size_t i = 0; i < exact[l].size(); ++i)
      if (__builtin_add_overflow(exact[l][i], part[l][i], &sum))
        throw std::overflow_error("Film::add_exact: a sum would overflow 64 bits");
  }
  for (size_t l = 0; l < kLayerCount; ++l)
    for (size_t i = 0; i < exact[l].size(); ++i) exact[l][i] += part[l][i];
  frames = frames_after - 1;
  finish_frame();
}

void Film::refresh_sums() {
  if (mode != FilmMode::kFull) return;
  for (size_t l = 0; l < kLayerCount; ++l) {
    const std::vector<int64_t>& from = exact[l];
    std::vector<float>& to = sums[l];
    to.resize(from.size());
    for (size_t i = 0; i < from.size(); ++i) to[i] = static_cast<float>(static_cast<double>(from[i]) * unit);
  }
}

void Film::finish_frame() {
  ++frames;
  if (mode != FilmMode::kFull) return;
  refresh_sums();
  if (!is_power_of_two(frames)) return;
  // The oldest snapshot's buffers are reused for the newest.
  std::rotate(checkpoints.rbegin(), checkpoints.rbegin() + 1, checkpoints.rend());
  PassSnapshot& newest = checkpoints.front();
  newest.frames = frames;
  for (int p = 0; p < kPassCount; ++p) {
    const auto& sum = sums[static_cast<size_t>(layer_of(static_cast<Pass>(p)))];
    newest.sums[static_cast<size_t>(p)].assign(sum.begin(), sum.end());
  }
}

void Film::reset(const RenderSettings& settings) { reset(settings.width, settings.height, layers_needed(settings)); }

Image layer_average(const Film& film, Layer layer) {
  Image image{film.width, film.height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  const auto& sum = film.sums[static_cast<size_t>(layer)];
  if (sum.empty() || film.frames == 0) return image;
  const float scale = 1.0f / static_cast<float>(film.frames);
  for (size_t i = 0; i < sum.size(); ++i) image.rgb[i] = sum[i] * scale;
  return image;
}

Image combine_passes(const Film& film, const std::array<bool, kPassCount>& enabled,
                     const std::array<float, kPassCount>& weights) {
  Image image{film.width, film.height, std::vector<float>(3 * film.pixel_count(), 0.0f)};
  if (film.frames == 0) return image;
  for (int p = 0; p < kPassCount; ++p) {
    const auto& sum = film.sums[static_cast<size_t>(p)];
    if (!enabled[static_cast<size_t>(p)] || sum.empty()) continue;
    const float scale = weights[static_cast<size_t>(p)] / static_cast<float>(film.frames);
    for (size_t i = 0; i < sum.size(); ++i) image.rgb[i] += sum[i] * scale;
  }
  return image;
}

}  // namespace lueur
