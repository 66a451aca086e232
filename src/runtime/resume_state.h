// The resume state of a render: everything needed to go on accumulating where it stopped (the film's exact sums and
// noise snapshots, and the L1 store beside it), with the settings it was made with, so that a resumed render ends
// with the bytes of an uninterrupted one. Depends on the integrator's Accumulation (film and store).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "integrator/renderer.h"

namespace lueur {

/// What must not change between a render and its resumption: one line per setting that decides the sums
/// ("--l1-rays 16"), and the scene. The state file keeps it; resuming compares it line by line.
using RenderIdentity = std::vector<std::string>;

/// The state of `sides` (one, or two for an A/B split) after their frames, as bytes ending in a checksum.
std::string encode_resume_state(const RenderIdentity& identity, const std::vector<const Accumulation*>& sides);

/// Restores `sides` (reset beforehand with the settings they were made with) from `bytes`. Throws
/// std::runtime_error with one line naming the problem: not a state file, cut short or altered, another
/// version, a setting or the scene that differs (the first line that differs, as it was and as it is now), images
/// of another size or passes.
void decode_resume_state(std::string_view bytes, const RenderIdentity& identity,
                         const std::vector<Accumulation*>& sides);

}  // namespace lueur
