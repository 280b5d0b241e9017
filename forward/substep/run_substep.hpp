// The substep solver's run: each step is a short pipeline of named stages
//   find_pairs -> collide -> prepare (masses, contacts, colours)
//   -> substeps x [integrate_velocities, warm_start, solve (soft), integrate_positions,
//                  relax, advance_slip]
// after Box2D v3's soft step, with DDA blocks: each block keeps Shi's six unknowns and
// answers an impulse through its effective inverse mass (substep_types.hpp). Cost grows
// with the number of contact points, not with a global factorisation. The step's stages
// are advance_step.hpp's, the quiet start before the clock runs quiet_start.hpp's; this file
// holds the run loop and the end of a run whose blocks all sleep.
#pragma once

#include "forward/block_system.hpp"
#include "forward/run_record.hpp"
#include "forward/run_summary.hpp"

namespace ddafit {

void run_substep(const Scene& scene, BlockSystem& system, RunRecorder& recorder, SimulationSummary& summary);

}  // namespace ddafit
