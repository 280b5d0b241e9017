// What both solvers record of a run: the output schedule, the history of the
// measurement points, their running extremes, and the progress calls.
#pragma once

#include <chrono>

#include "forward/contact/overlap.hpp"
#include "forward/run_summary.hpp"

namespace ddafit {

// Velocity of a measurement point: T(p) times its block's velocity.
Vec2 point_velocity(const BlockSystem& system, const MaterialPoint& point);

// The worst overlap of the run into the solver's report (summary.json).
void report_overlap(const BlockSystem& system, const WorstOverlap& worst, SolverReport& report);

// The deepest overlap, as a share of the smaller free block of its pair, that ddafit's runs are
// checked to: the contact class tests (tests/contact_scene_audit.hpp), the substep scenes and the
// Vajont sections I-X (docs/vajont.md) all hold it. Deeper, the blocks have sunk into each other
// by more than the contact rules were verified at, and what a run reports near them is less sure.
inline constexpr double kOverlapBoundRatio = 0.01;

// The warning for a run that completed with its worst overlap over kOverlapBoundRatio, naming
// the two blocks and what to change on the solver that ran, or "". simulate() adds it to the
// summary's warnings (summary.json; stderr unless --quiet).
std::string overlap_warning(const Scene& scene, const SolverReport& report);

class RunRecorder {
 public:
  RunRecorder(const Scene& scene, const SimulationHooks& hooks, SimulationResult& result);

  // Records t = 0.
  void start(const BlockSystem& system);

  // The step to attempt from `time`: `step`, or, when the next output time (or the end)
  // is within a hair of a step away, the step that lands on it exactly, so that rows fall
  // on multiples of the interval without round-off drift. *landing is then that time, else -1.
  double fit_step(double time, double step, double* landing) const;

  // As fit_step, but the time to the next output (or the end) is cut into equal steps, as
  // few as steps no longer than `step` allow: no sliver is left before an output time. The
  // substep solver's: a sliver's substep h sets its impact margins (|g| h, converge_impacts.hpp)
  // so tight that the sweeps' ordinary residuals counted as impacts (a slab's 0.4 ms steps
  // with outputs every 10.4 ms: 300 impact groups against 37, 2.4 % off seed Eq. 4).
  double even_step(double time, double step, double* landing) const;

  // After an accepted step that ended at `time`: extremes every step, a history row at
  // output times and at the end, and a progress call about once per second of wall time.
  void record(double time, const BlockSystem& system);

  // A history row now, whatever the schedule (the last state of a failed run).
  void record_row(double time, const BlockSystem& system);

  bool finished(double time) const { return time >= scene_.duration - end_slack_; }

  // Whether the caller asked the run to stop (SimulationHooks::should_stop). If so, the
  // summary says Interrupted at `time` and the history ends with a row there.
  bool interrupted(double time, const BlockSystem& system);

 private:
  double next_row_time() const;  // the next output time, or the end

  const Scene& scene_;
  const SimulationHooks& hooks_;
  SimulationResult& result_;
  long output_count_ = 1;  // outputs at multiples of the interval, without summing round-off
  double next_output_ = 0.0;
  double end_slack_ = 0.0;
  std::chrono::steady_clock::time_point last_progress_;
};

}  // namespace ddafit
