// The implicit solver's run (Shi's DDA): each step runs the stages of forward/step/ in
// order (find contacts -> open-close iteration [assemble, solve, check contacts] ->
// accept or redo -> update blocks) on one global sparse system.
#pragma once

#include "forward/block_system.hpp"
#include "forward/run_record.hpp"
#include "forward/run_summary.hpp"

namespace ddafit {

void run_implicit(const Scene& scene, BlockSystem& system, RunRecorder& recorder, SimulationSummary& summary);

// The normal penalty of a scene: control.penalty, or penalty_factor x the largest
// Young's modulus (Shi's rule of thumb).
double automatic_penalty(const Scene& scene);

}  // namespace ddafit
