// What a forward run gives back and who may watch it: the history rows, the per-point
// extremes, the counters and solver report of summary.json, the run's status (failure is a
// value), and the optional hooks. Below both solvers and the run recorder, which fill it;
// forward/simulation.hpp, the one call above them, returns it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/scene.hpp"
#include "forward/step_profile.hpp"

namespace ddafit {

struct HistoryRow {
  double time = 0.0;
  int point = 0;  // index into Scene::measure
  Vec2 position = Vec2::Zero();
  Vec2 displacement = Vec2::Zero();  // since t = 0
  Vec2 velocity = Vec2::Zero();
};

struct PointSummary {
  std::string name;
  double max_lateral_displacement = 0.0;  // max |u_x|, m
  double max_total_displacement = 0.0;    // max |u|, m
  double peak_lateral_velocity = 0.0;     // max |v_x|, m/s
  double peak_total_velocity = 0.0;       // max |v|, m/s
  double duration = 0.0;  // last time the point's speed was >= rest_speed, s
  bool stopped = false;   // speed below rest_speed at the end of the run
};

// The per-point results, one row each: the name summary.json and a study's observations
// use, the unit, and how to read and write the PointSummary field (`stopped` as 1 or 0;
// `flag` says it is written as true/false). Every list of the quantities (summary.json, the
// run codec, the evaluation cache, a study's allowed names) iterates this table.
struct PointQuantity {
  const char* name;
  const char* unit;
  bool flag;
  double (*get)(const PointSummary&);
  void (*set)(PointSummary&, double);
};

inline constexpr PointQuantity kPointQuantities[] = {
    {"max_lateral_displacement", "m", false, [](const PointSummary& p) { return p.max_lateral_displacement; },
     [](PointSummary& p, double v) { p.max_lateral_displacement = v; }},
    {"max_total_displacement", "m", false, [](const PointSummary& p) { return p.max_total_displacement; },
     [](PointSummary& p, double v) { p.max_total_displacement = v; }},
    {"peak_lateral_velocity", "m/s", false, [](const PointSummary& p) { return p.peak_lateral_velocity; },
     [](PointSummary& p, double v) { p.peak_lateral_velocity = v; }},
    {"peak_total_velocity", "m/s", false, [](const PointSummary& p) { return p.peak_total_velocity; },
     [](PointSummary& p, double v) { p.peak_total_velocity = v; }},
    {"duration", "s", false, [](const PointSummary& p) { return p.duration; },
     [](PointSummary& p, double v) { p.duration = v; }},
    {"stopped", "", true, [](const PointSummary& p) { return p.stopped ? 1.0 : 0.0; },
     [](PointSummary& p, double v) { p.stopped = v != 0.0; }},
};

struct RunCounters {
  long steps = 0;
  long open_close_iterations = 0;
  long step_cuts = 0;       // steps redone with a shorter time step
  long penalty_raises = 0;  // steps redone with a stiffer penalty
  long unsettled_contacts = 0;  // contact-steps accepted while still changing state
  long symbolic_analyses = 0;   // sparse orderings: the contact graph changed
  long factorizations = 0;      // Cholesky factorisations (one per open-close pass unless CG)
  long cg_solves = 0;           // passes solved by CG on an older factor (reuse_factorization)
  long factor_updates = 0;      // passes solved on the last factor updated by rank-one terms (update_factorization)
  long update_rank = 0;         // rank-one terms those updates applied
  double final_penalty = 0.0;
  double smallest_step = 0.0;
  double largest_step = 0.0;
  double simulated_time = 0.0;
};

// Which solver ran, why, and what the substep solver measured of its contacts.
struct SolverReport {
  Integrator integrator = Integrator::Implicit;  // the one that ran (never Auto)
  std::string reason;                            // why: the scene's choice or the Auto rule
  int substeps = 0;                              // per step (substep solver)
  double deep_overlap_ratio = 0.0;               // control.deep_overlap_ratio as resolved (substep solver)
  // J/m: what the quiet start's overlaps can give back by lifting blocks, sum F delta at t = 0; the
  // energy audit credits it against the blocks that rise (EnergyAudit::stored_contact; substep solver)
  double stored_contact_energy = 0.0;
  // The quiet start (substep solver, control.quiet_start_steps): the steps it ran, and the
  // largest change of a normal impulse over its last step, as a share of the largest impulse
  // (it stops once that is under 1e-4; a slope that is not in equilibrium runs every step).
  int quiet_start_steps = 0;
  double quiet_start_change = 0.0;
  long contact_points = 0;                       // summed over steps (mean = / steps)
  double worst_penetration = 0.0;                // m, deepest overlap at the end of a step
  double worst_penetration_ratio = 0.0;          // that depth / the smaller block's size
  double worst_penetration_time = 0.0;           // s
  std::string worst_penetration_at;              // the two blocks
  long unconverged_points = 0;  // point-steps still closing faster than the tolerance after the last sweep
  long fast_steps = 0;          // steps in which a block moved further than the contact margin allows
  long sleeping_block_steps = 0;  // summed over steps: blocks asleep (control.sleep_time)
  long wakes = 0;                 // sleeping groups woken by a moving block
  double all_asleep_time = -1.0;  // s: when every free block slept and the run recorded its rest at once; -1 never
  long steps_on_one_thread = 0;   // substep solver: steps the thread governor ran on one thread (forward/thread_governor.hpp)
  // Substep solver, impact groups (forward/substep/converge_impacts.hpp): groups solved
  // directly, groups past 160 points (an impact's solved in pieces, a settling one's left to the
  // sweeps), the pieces' solves, solves undone (energy), and the solves (groups' and pieces')
  // that solved friction with the normals beside a heavy block (solve_group_friction.hpp).
  long impact_groups = 0;
  long impact_groups_too_large = 0;
  long impact_group_pieces = 0;
  long impact_groups_refused = 0;
  long impact_groups_with_friction = 0;
};

// Interrupted: the caller asked the run to stop (SimulationHooks::should_stop) before the
// end; the history and extremes up to that time are kept.
enum class RunStatus { Completed, InvalidScene, Failed, Interrupted };

struct SimulationSummary {
  RunStatus status = RunStatus::Completed;
  std::string message;  // the diagnosis when status != Completed
  std::vector<std::string> warnings;  // settings known to degrade results (docs/theory.md)
  std::vector<PointSummary> points;
  // The top of the blocks at the end of a run that reached its duration (forward/
  // top_surface.hpp; empty otherwise): the ground surface the run leaves, for a deposit's
  // comparison with a surveyed one.
  std::vector<Vec2> final_surface;
  RunCounters run;
  StepProfile profile;
  SolverReport solver;
};

// The sled's own record (time.integrator: sled; forward/sled/sled.hpp): its static friction
// angle and its distance and speed along the path at every step. Empty for the DDA solvers.
struct SledPoint {
  double time = 0.0;      // s
  double distance = 0.0;  // m along the path
  double velocity = 0.0;  // m/s
};
struct SledRecord {
  double static_friction_angle = 0.0;  // deg: the basal friction at which the sled is just stable
  double path_length = 0.0;            // m
  int slices = 0;
  std::vector<SledPoint> series;
};

struct SimulationResult {
  SimulationSummary summary;
  std::vector<HistoryRow> history;
  SledRecord sled;
};

// Optional observers of a run. None of them may throw.
struct SimulationHooks {
  // Called at every output time (t = 0, each output interval, and the end).
  std::function<void(double time, const BlockSystem& system)> on_output;
  // Called about once per second of wall time with the simulated time reached.
  std::function<void(double time, double duration)> on_progress;
  // Asked once per step; true stops the run there with status Interrupted (the command
  // line sets it on SIGINT and SIGTERM).
  std::function<bool()> should_stop;
};

}  // namespace ddafit
