// What every stage of the implicit solver's step shares, after Box2D v3's b2StepContext:
// the scene and its options, the blocks, this step's contacts and the copy a redo restores,
// the time-step control, the global system K D = F and its solver, and the run's counters.
// A stage's signature then says what it may touch: the context, and the step's
// parameters (StepParameters) where the attempt matters.
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/run_summary.hpp"
#include "forward/scene.hpp"
#include "forward/sparse_system.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/control_time_step.hpp"

namespace ddafit {

struct ImplicitStepContext {
  ImplicitStepContext(const Scene& scene, BlockSystem& system, SimulationSummary& summary,
                      const SolverOptions& solver_options)
      : scene(scene), options(scene.options), system(system), solver(solver_options), profile(summary.profile),
        run(summary.run) {}

  const Scene& scene;
  const SimulationOptions& options;
  BlockSystem& system;
  ContactDetection detection;
  ContactSet contacts;
  ContactSet saved;  // the step's contacts before its first attempt: what a redo restores
  TimeStepControl control;
  SparseSolver solver;
  GlobalSystem equations;
  WorstOverlap worst;  // deepest overlap at the end of an accepted step, so far
  // Per block: steps left in which it counts as just collided (resolve_impacts.cpp).
  std::vector<int> collision_steps_left;
  StepProfile& profile;
  RunCounters& run;
};

}  // namespace ddafit
