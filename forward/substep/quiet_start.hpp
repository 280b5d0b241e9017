// The quiet start (docs/theory.md §13): before the clock runs, the contacts touching at t = 0
// take up the weight, the blocks resting on the ground stepped from rest until no contact's
// impulse changes, so that the run starts from loaded contacts instead of a bounce. A block
// resting off balance turns in each of those steps; where that would start it turned, the
// quiet start is done again at steps short enough to keep it where it was given
// (docs/theory.md, Known limits (k)).
#pragma once

#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/scene.hpp"
#include "forward/substep/substep_context.hpp"

namespace ddafit {

// A block the quiet start turned by more than this, rad, is settled again at shorter steps, and
// named in a warning if it still turned that much.
inline constexpr double kQuietStartTurnLimit = 0.01;

// Runs the quiet start on `w` (its blocks, contacts and sweep state). Returns a problem found on
// the way ("" if none); adds to `warnings` a block it left turned by more than
// kQuietStartTurnLimit.
std::string settle_before_the_clock(SubstepContext& w, std::vector<std::string>& warnings);

// The warning for the free block turned most from `given` (the vertices before the quiet start),
// if it turned more than kQuietStartTurnLimit; "" otherwise.
std::string quiet_start_warning(const Scene& scene, const BlockSystem& s, const std::vector<Vec2>& given);

}  // namespace ddafit
