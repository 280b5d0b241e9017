// Stage 1c of a step, before the open-close iteration: impacts are resolved as impulses.
#pragma once

#include <vector>

#include "forward/step/implicit_context.hpp"

namespace ddafit {

// A point closing within the step at the speed it has would meet its penalty spring at
// full speed. The spring stops it inside the step, and DDA's velocity update
// V1 = 2 D / dt - V0 then hands the approach velocity back (D ~ 0 gives V1 ~ -V0): an
// elastic bounce at any penalty, which a normal dashpot cannot remove; and the impact's
// force, m v / dt, compresses the block elastically, which springs back the next step.
// A rock impact is taken as perfectly inelastic and rigid, as in the substep solver
// (docs/theory.md §3): before the step, at every point that would close within it
// (gap g >= 0 at the start, normal speed v_n < -g / dt), an impulse on the blocks' rigid
// motion (mass and moment of inertia; their strain rates untouched) slows v_n to -g / dt,
// so the point closes at the end of the step; with it goes a Coulomb friction impulse of
// at most tan(phi) times the normal one (Mohr-Coulomb, seed Eq. 2-3 for phi), which may
// stop the slip but not reverse it. `time_step` is the step the impulses are sized for.
// Changes the blocks' velocities (the V0 of the step); returns how many points it stopped
// and marks in `struck` (one entry per block) the free blocks of the impact groups that
// collide (fastest approach beyond 3 |g| dt) or hold a block that collided within the last 20
// steps; groups approaching slower are settled, not struck.
int resolve_impacts(ImplicitStepContext& ctx, double time_step, std::vector<char>& struck);

}  // namespace ddafit
