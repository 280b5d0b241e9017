// The stages of one substep-solver step, shared by the run (run_substep.cpp) and its quiet
// start: find the step's contacts, advance the blocks over the step's substeps, and measure
// what the contacts left (the deepest overlap, the points still closing).
#pragma once

#include <string>

#include "forward/substep/substep_context.hpp"

namespace ddafit {

// Relative normal velocity, as a fraction of the largest step displacement per step,
// that a touching point may keep after the last sweep and still count as converged.
inline constexpr double kConvergedVelocityRatio = 1e-2;

// Broad and narrow phase: this step's manifolds, carrying over the last step's impulses.
// Empty, or what is wrong with the scene (two blocks touching without an interface).
std::string find_step_contacts(SubstepContext& w);

// A step of length dt on this step's manifolds: the substeps (velocities, contact sweeps,
// moves, slip), the position correction, then the blocks move once and each deformable
// block takes its stress from its contacts. `measured` false: a quiet-start step, before
// the clock runs (no earthquake, the measurement points' origins move with the blocks).
void advance_step(SubstepContext& w, double dt, bool measured);

// After a step ending at `time`: the deepest overlap (relative to the smaller block of its
// pair) into the report, and the points still closing faster than `converged_speed`.
void measure_contacts(SubstepContext& w, double time, double converged_speed);

}  // namespace ddafit
