// The substep solver's promise that 1 and 2 threads give the same numbers bit for bit: a scene run
// on two threads and on one, every history row and the contact census compared exactly (no
// tolerance: the graph colouring and the groups of the list-order sweeps fix the order of every
// floating-point operation whatever the thread count).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <string>

#include "forward/simulation.hpp"

namespace ddafit {

inline void expect_same_on_one_and_two_threads(Scene scene, const std::string& label) {
  scene.options.threads = 2;
  // Two threads first: the run on one thread then leaves OpenMP at one thread, as CTest starts
  // every test (OMP_NUM_THREADS=1), for the tests that follow in this process.
  const SimulationResult b = simulate(scene);
  scene.options.threads = 1;
  const SimulationResult a = simulate(scene);
  ASSERT_EQ(a.summary.status, RunStatus::Completed) << label << ": " << a.summary.message;
  ASSERT_EQ(b.summary.status, RunStatus::Completed) << label << ": " << b.summary.message;
  EXPECT_EQ(a.summary.run.steps, b.summary.run.steps) << label;
  ASSERT_EQ(a.history.size(), b.history.size()) << label;
  ASSERT_FALSE(a.history.empty()) << label;
  int mismatches = 0;  // rows that differ; the comparison stops after 10 of them
  size_t compared = 0;
  for (size_t i = 0; i < a.history.size() && mismatches < 10; ++i, ++compared) {
    const HistoryRow &x = a.history[i], &y = b.history[i];
    const bool same = x.time == y.time && x.point == y.point && x.position == y.position &&
                      x.displacement == y.displacement && x.velocity == y.velocity;
    EXPECT_TRUE(same) << label << ", row " << i << " at t = " << x.time << ": position (" << x.position.transpose()
                      << ") against (" << y.position.transpose() << "), velocity (" << x.velocity.transpose()
                      << ") against (" << y.velocity.transpose() << ")";
    if (!same) ++mismatches;
  }
  const SolverReport &p = a.summary.solver, &q = b.summary.solver;
  EXPECT_EQ(p.contact_points, q.contact_points) << label;
  EXPECT_EQ(p.worst_penetration, q.worst_penetration) << label;
  // The step's measurement runs in contiguous shares whose worst are taken in order
  // (advance_step.cpp, measure_contacts): the same pair and time on either count.
  EXPECT_EQ(p.worst_penetration_at, q.worst_penetration_at) << label;
  EXPECT_EQ(p.worst_penetration_time, q.worst_penetration_time) << label;
  EXPECT_EQ(p.unconverged_points, q.unconverged_points) << label;
  std::cout << "[measured] " << label << ": " << compared << " of " << a.history.size() << " rows compared, "
            << mismatches << " differ; mean contact points per step "
            << p.contact_points / std::max(1L, a.summary.run.steps) << "\n";
}

}  // namespace ddafit
