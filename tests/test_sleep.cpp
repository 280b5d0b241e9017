// Sleeping (forward/substep/sleep.hpp, issue "Model no more than a scene needs"): a group of
// touching blocks at rest sleeps and wakes when a moving block comes near; what the run
// reports must not change beyond the run's own spread, and a scene that never comes to
// rest must give the same numbers bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

Scene substep(Scene s, double sleep_time) {
  s.options.integrator = Integrator::Substep;
  s.options.sleep_time = sleep_time;
  return s;
}

TEST(Sleeping, AStackAtRestSleepsAndStaysWhereItWas) {
  Scene stack = verification::stack_scene();
  stack.duration = 3.0;
  const SimulationResult awake = simulate(substep(stack, 0.0));
  const SimulationResult slept = simulate(substep(stack, 0.5));
  ASSERT_EQ(slept.summary.status, RunStatus::Completed) << slept.summary.message;
  EXPECT_EQ(awake.summary.solver.sleeping_block_steps, 0);
  EXPECT_LT(awake.summary.solver.all_asleep_time, 0.0);
  // Its five blocks, the only free ones, all sleep from about 0.5 s on (0.5 s at rest after
  // the quiet start); then nothing can move again and the run stops stepping: it takes at
  // most half the awake run's steps and still ends at 3 s with a row at every output time.
  const double asleep = slept.summary.solver.all_asleep_time;
  EXPECT_GE(asleep, 0.5);
  EXPECT_LT(asleep, 1.5);
  EXPECT_LT(slept.summary.run.steps, awake.summary.run.steps / 2);
  EXPECT_DOUBLE_EQ(slept.summary.run.simulated_time, stack.duration);
  ASSERT_EQ(slept.history.size(), awake.history.size());
  for (size_t k = 0; k < slept.history.size(); ++k) {
    const HistoryRow& row = slept.history[k];
    EXPECT_NEAR(row.time, awake.history[k].time, 1e-9);
    if (row.time <= asleep) continue;
    // Asleep: each point where it was when the last block fell asleep, and still.
    const HistoryRow& last = slept.history[k - stack.measure.size()];
    if (last.time >= asleep) {
      EXPECT_EQ(row.displacement, last.displacement);
    }
    EXPECT_EQ(row.velocity, Vec2::Zero());
  }
  for (size_t p = 0; p < stack.measure.size(); ++p)  // at rest either way: within 0.1 mm
    EXPECT_NEAR(slept.summary.points[p].max_total_displacement, awake.summary.points[p].max_total_displacement, 1e-4);
}

TEST(Sleeping, ABlockFallingOntoASleepingStackWakesItAndLandsAsOnAnAwakeOne) {
  Scene s = verification::stack_scene();
  s.duration = 3.0;
  // A 1 m block 8 m above the stack's top falls for about 1.3 s, long after the stack slept.
  double top = -1e9;
  for (const BlockInput& b : s.blocks)
    for (const Vec2& v : b.polygon) top = std::max(top, v.y());
  BlockInput falling = verification::block("falling", {{0.2, top + 8}, {1.2, top + 8}, {1.2, top + 9}, {0.2, top + 9}}, false);
  s.blocks.push_back(falling);
  s.measure.push_back({"falling", {0.7, top + 8.5}});
  const SimulationResult awake = simulate(substep(s, 0.0));
  const SimulationResult slept = simulate(substep(s, 0.5));
  ASSERT_EQ(slept.summary.status, RunStatus::Completed) << slept.summary.message;
  EXPECT_GE(slept.summary.solver.wakes, 1);
  EXPECT_GT(slept.summary.solver.sleeping_block_steps, 0);
  // The impact's outcome as without sleeping: the stack's points and the falling block's
  // drop within 1 mm (the stack sat a few um differently when the block arrived).
  for (size_t p = 0; p < s.measure.size(); ++p)
    EXPECT_NEAR(slept.summary.points[p].max_total_displacement, awake.summary.points[p].max_total_displacement, 1e-3)
        << s.measure[p].name;
}

TEST(Sleeping, ASlideThatNeverRestsGivesTheSameNumbers) {
  const Scene incline = verification::incline_scene({});
  const SimulationResult a = simulate(substep(incline, 0.0)), b = simulate(substep(incline, 0.5));
  EXPECT_EQ(b.summary.solver.sleeping_block_steps, 0);
  ASSERT_EQ(a.history.size(), b.history.size());
  for (size_t k = 0; k < a.history.size(); ++k) ASSERT_EQ(a.history[k].displacement, b.history[k].displacement);
}

TEST(Sleeping, AStandingWallSleepsWithinItsOwnSettling) {
  Scene wall = verification::brick_wall_scene(10, 10, 3.0);
  const SimulationResult awake = simulate(substep(wall, 0.0));
  const SimulationResult slept = simulate(substep(wall, 0.5));
  ASSERT_EQ(slept.summary.status, RunStatus::Completed) << slept.summary.message;
  // Its bricks touch one another: one group, which falls asleep at once, and the run then
  // records its last state to the end without steps.
  EXPECT_GE(slept.summary.solver.all_asleep_time, 0.5);
  EXPECT_LT(slept.summary.run.steps, awake.summary.run.steps);
  // The wall settles by some 10 um in the first steps and then stands: within 0.1 mm.
  for (size_t p = 0; p < wall.measure.size(); ++p)
    EXPECT_NEAR(slept.summary.points[p].max_total_displacement, awake.summary.points[p].max_total_displacement, 1e-4);
}

// A block sliding on a level floor at v0 stops where Coulomb says, at v0^2 / (2 mu g) after
// t_s = v0 / (mu g). Asleep (sleep_time 0.3 s) it must stop at the same place: sleeping acts
// only once it has rested, and then the run stops stepping, so every row up to the moment it
// fell asleep is the awake run's to the bit and every row after is the resting block. Swept
// over speeds, friction angles and block sizes: a rule that held for one slider could fail
// for a longer, slower or rougher one.
using Slide = std::tuple<double, double, double>;  // v0 m/s, friction angle deg, block width m
class SlideToRest : public ::testing::TestWithParam<Slide> {};

TEST_P(SlideToRest, AsleepWhereCoulombStopsItAndStillThere) {
  const auto [v0, phi, width] = GetParam();
  const double g = 9.81, mu = std::tan(phi * M_PI / 180.0);
  const double stop_time = v0 / (mu * g), stop = v0 * v0 / (2.0 * mu * g);
  Scene s = verification::incline_scene({});
  s.blocks.clear();
  s.interfaces[0].friction_angle = phi;
  s.interfaces[0].roughness_angle = 0.0;
  s.duration = stop_time + 1.5;
  s.blocks.push_back(verification::block("floor", {{-5, -2}, {40, -2}, {40, 0}, {-5, 0}}, true));
  const double height = 0.5 * width;  // low enough not to tip at mu <= 1 (mu h < w)
  BlockInput b = verification::block("slider", {{0, 0}, {width, 0}, {width, height}, {0, height}}, false);
  b.velocity = Vec2(v0, 0.0);
  s.blocks.push_back(b);
  s.measure = {{"c", {0.5 * width, 0.5 * height}}};
  const SimulationResult awake = simulate(substep(s, 0.0));
  const SimulationResult slept = simulate(substep(s, 0.3));
  ASSERT_EQ(awake.summary.status, RunStatus::Completed) << awake.summary.message;
  ASSERT_EQ(slept.summary.status, RunStatus::Completed) << slept.summary.message;
  // 0.1 mm, as the level landings of test_landing.cpp (the step's error is O(v dt^2)).
  EXPECT_NEAR(awake.history.back().displacement.x(), stop, 1e-4);
  EXPECT_NEAR(slept.history.back().displacement.x(), stop, 1e-4);
  // Asleep 0.3 s after it stopped (its speed falls under 1 % of rest_speed a hair before t_s),
  // give or take the 10 ms of its first steps at rest.
  const double asleep = slept.summary.solver.all_asleep_time;
  EXPECT_GT(asleep, stop_time + 0.3 - 0.02);
  EXPECT_LT(asleep, stop_time + 0.3 + 0.02);
  EXPECT_LT(slept.summary.run.steps, awake.summary.run.steps);
  ASSERT_EQ(slept.history.size(), awake.history.size());
  for (size_t k = 0; k < slept.history.size(); ++k) {
    const HistoryRow &row = slept.history[k], &same = awake.history[k];
    ASSERT_DOUBLE_EQ(row.time, same.time);
    if (row.time < asleep) {
      EXPECT_EQ(row.displacement, same.displacement) << "t = " << row.time;
    } else {
      EXPECT_EQ(row.velocity, Vec2::Zero()) << "t = " << row.time;
      EXPECT_NEAR(row.displacement.x(), same.displacement.x(), 1e-6) << "t = " << row.time;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sweep, SlideToRest,
                         ::testing::Combine(::testing::Values(1.0, 4.0), ::testing::Values(15.0, 30.0, 45.0),
                                            ::testing::Values(0.5, 2.0)));

}  // namespace
}  // namespace ddafit
