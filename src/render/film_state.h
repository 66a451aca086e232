// The resume state of a render: everything needed to go on accumulating where it stopped (the exact sums, the noise
// estimate's snapshots, the L1 store), with the settings it was made with, so that a resumed render ends with the
// bytes of an uninterrupted one. Depends on the film.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "render/film.h"

namespace lueur {

/// What must not change between a render and its resumption: one line per setting that decides the sums
/// ("--l1-rays 16"), and the scene. The state file keeps it; resuming compares it line by line.
using RenderIdentity = std::vector<std::string>;

/// The state of `films` (one, or two for an A/B split) after their frames, as bytes ending in a checksum.
std::string encode_film_state(const RenderIdentity& identity, const std::vector<const Film*>& films);

/// Restores `films` (reset beforehand with the settings they were made with) from `bytes`. Throws
/// std::runtime_error with one line naming the problem: not a state file, cut short or altered, another
/// version, a setting or the scene that differs (the first line that differs, as it was and as it is now), images
/// of another size or passes.
void decode_film_state(std::string_view bytes, const RenderIdentity& identity, const std::vector<Film*>& films);

}  // namespace lueur
