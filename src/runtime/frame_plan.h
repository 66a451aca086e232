// How a batch render's frames are dealt out to workers of unequal speed (lueur-mpi's ranks) in rounds. Pure
// arithmetic, so that it is tested without MPI. Which frames a worker renders never changes the image (the film's
// sums are exact): only when everybody finishes.
#pragma once

#include <cstdint>
#include <vector>

namespace lueur {

/// Splits `count` frames among workers in proportion to their `rates` (frames per second; a rate that is not
/// positive counts as the mean of the others, or all as equal when none is known), by largest remainder with ties
/// to the lower index. The shares sum to `count`.
std::vector<uint64_t> share_frames(uint64_t count, const std::vector<double>& rates);

/// The end of a round that starts after `done` frames: `wanted` frames more (at least 1), but never past `total`
/// and never past the next power of two of the frame count from `snapshots_from` on, where the noise estimate takes
/// its snapshot (Film::add_exact).
uint64_t round_end(uint64_t done, uint64_t wanted, uint64_t total, uint64_t snapshots_from = 0);

/// Each worker's frames in the round that starts after `done`: about `seconds` of work each at its rate (at least
/// one frame; one frame for a rate not yet known), so that all finish together. Within two such rounds of the next
/// stop (round_end: a power of two or the end), the round goes to the stop instead, its frames shared out by rate,
/// so that no short round is left. The shares sum to the round's end less `done`.
std::vector<uint64_t> plan_round(uint64_t done, uint64_t total, uint64_t snapshots_from,
                                 const std::vector<double>& rates, double seconds);

}  // namespace lueur
