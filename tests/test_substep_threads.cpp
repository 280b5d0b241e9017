// The substep solver's promise that 1 and 2 threads give the same numbers bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "forward/geometry.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

Vec2 centroid_of(const std::vector<Vec2>& polygon) { return polygon_moments(polygon).centroid; }

// --- 6. Thread determinism of the substep solver --------------------------------------

// A loop runs on several threads only from kParallelMinimum (512) items up; the contact
// sweeps run colour by colour, each colour of 64 manifolds or more on both threads in
// static shares (solve_contacts.cpp; 512 before model revision 2026-11-27.2). The
// 20 x 30 wall (600 bricks, 1731 manifolds) has six colours of 261-315 manifolds, which the
// old threshold kept on one thread, so this test takes a larger wall. This 40 x 30 wall
// (1200 bricks, 3491 manifolds at t = 0) has six colours of 551-615, so every loop of the
// step runs on both threads; the quiet start, which takes most of the run time, runs the
// same sweeps and is compared through the rows of t = 0. The thread governor
// (forward/thread_governor.hpp) may then run steps on one thread where that is faster, but
// it times every pair of windows on both threads as well, starting with the quiet start's
// first 16 steps, so both counts are in the two-thread run. The graph colouring makes the
// order of every floating-point operation independent of the thread count: the histories
// must agree bit for bit, not within a tolerance.
TEST(SubstepScenesThreads, OneAndTwoThreadsAgreeBitForBit) {
  Scene one = verification::brick_wall_scene(40, 30, 0.05);
  one.options.integrator = Integrator::Substep;
  // Every brick's centre is measured, not only the top one: 1200 points x 6 output times.
  for (const BlockInput& b : one.blocks)
    if (!b.fixed) one.measure.push_back({b.name, centroid_of(b.polygon)});
  one.options.threads = 1;
  Scene two = one;
  two.options.threads = 2;
  // Two threads first: the run on one thread then leaves OpenMP at one thread, as CTest
  // starts every test (OMP_NUM_THREADS=1), for the tests that follow in this process.
  const SimulationResult b = simulate(two);
  const SimulationResult a = simulate(one);
  ASSERT_EQ(a.summary.status, RunStatus::Completed) << a.summary.message;
  ASSERT_EQ(b.summary.status, RunStatus::Completed) << b.summary.message;
  EXPECT_EQ(a.summary.run.steps, b.summary.run.steps);
  ASSERT_EQ(a.history.size(), b.history.size());
  ASSERT_FALSE(a.history.empty());
  int mismatches = 0;  // rows that differ; the comparison stops after 10 of them
  size_t compared = 0;
  for (size_t i = 0; i < a.history.size() && mismatches < 10; ++i, ++compared) {
    const HistoryRow &x = a.history[i], &y = b.history[i];
    const bool same = x.time == y.time && x.point == y.point && x.position == y.position &&
                      x.displacement == y.displacement && x.velocity == y.velocity;
    EXPECT_EQ(x.time, y.time) << "row " << i;
    EXPECT_EQ(x.point, y.point) << "row " << i;
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(x.position[k], y.position[k]) << "row " << i;
      EXPECT_EQ(x.displacement[k], y.displacement[k]) << "row " << i;
      EXPECT_EQ(x.velocity[k], y.velocity[k]) << "row " << i;
    }
    if (!same) ++mismatches;
  }
  EXPECT_EQ(a.summary.solver.contact_points, b.summary.solver.contact_points);
  EXPECT_EQ(a.summary.solver.worst_penetration, b.summary.solver.worst_penetration);
  // The step's measurement runs in contiguous shares whose worst are taken in order
  // (advance_step.cpp, measure_contacts): the same pair and time on either count.
  EXPECT_EQ(a.summary.solver.worst_penetration_at, b.summary.solver.worst_penetration_at);
  EXPECT_EQ(a.summary.solver.worst_penetration_time, b.summary.solver.worst_penetration_time);
  EXPECT_EQ(a.summary.solver.unconverged_points, b.summary.solver.unconverged_points);
  std::cout << "[measured] threads: " << compared << " of " << a.history.size() << " rows compared, " << mismatches
            << " differ; mean contact points per step " << a.summary.solver.contact_points / std::max(1L, a.summary.run.steps)
            << "\n";
}

}  // namespace
}  // namespace ddafit
