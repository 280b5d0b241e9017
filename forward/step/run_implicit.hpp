// The implicit solver's run (Shi's DDA): each step runs the stages of forward/step/ in
// order (find contacts, new_points -> open_close_iterate [assemble, solve, check_contacts]
// -> judge_step: accept, stiffer or shorter -> update_blocks) on one global sparse system,
// every stage working on one ImplicitStepContext (implicit_context.hpp).
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
