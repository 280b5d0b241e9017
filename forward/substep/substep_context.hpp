// The substep solver's step context (forward/substep/advance_step.cpp and run_substep.cpp share it).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/earthquake/ground_motion.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/run_summary.hpp"
#include "forward/scene.hpp"
#include "forward/substep/sleep.hpp"
#include "forward/substep/solve_contacts.hpp"
#include "forward/substep/substep_types.hpp"
#include "forward/thread_governor.hpp"

namespace ddafit {

// What every stage of the substep solver's step shares, after Box2D v3's b2StepContext:
// the scene, the blocks, the contacts and the sweeps' state, the per-block bounds that set
// the step and the margins, and where the run's profile and solver report go.
struct SubstepContext {
  SubstepContext(const Scene& scene, BlockSystem& system, SimulationSummary& summary)
      : scene(scene), options(scene.options), system(system), profile(&summary.profile), report(summary.solver) {}

  const Scene& scene;
  const SimulationOptions& options;
  BlockSystem& system;
  StepProfile* profile;  // the quiet start points it at a scratch profile: its time is `settle`'s
  SolverReport& report;
  double max_move = 0.0;  // m, the largest move of a vertex in contact per step
  // Overlap at which a point counts as deep (position correction, converge_deep), as a share of
  // the smaller block of its pair: control.deep_overlap_ratio, resolved (options.hpp).
  double deep_overlap_ratio = kDeepOverlapLargeScene;
  GroundTrack ground;     // the earthquake, if any (forward/earthquake/ground_motion.hpp)
  double time = 0.0;      // s, the start of the step being advanced
  double load_work = 0.0; // J/m: the ground's inertial load's work in the last step, substep by substep
  ThreadGovernor threads{threads_allowed()};  // how many threads each step uses (thread_governor.hpp)
  double last_substep = 0.0;  // s, the last step's substep length (0 before the first): rescale_warm_start
  bool settling = false;  // the quiet start: no impact groups (converge_impacts.hpp), nothing strikes

  ContactDetection detection;
  PositionCorrection correction;
  ContactSet contacts;
  WorstOverlap worst;
  SweepState state;  // velocities, step moves and masses the sweeps work on
  std::vector<std::vector<int>> colours;
  std::vector<Vec3> start_velocity, moves;
  std::vector<char> deformable;  // per material: keeps its strain unknowns
  std::vector<double> reach;  // per block: largest distance of a vertex from the centroid
  std::vector<char> near;      // per block: had a contact point within the margin last step
  std::vector<double> extra_reach;  // per block: how far its step travel exceeds the margin's cover
  SleepState sleep;                 // which blocks sleep (off unless control.sleep_time > 0)
};

}  // namespace ddafit
