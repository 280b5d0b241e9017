// The quiet start's length (control.quiet_start_steps, substep solver). Before the clock runs,
// the blocks resting on the ground are held at rest at the start of each quiet step while their
// contacts take up the weight (forward/substep/quiet_start.cpp). A block that is in equilibrium
// does not move and its impulses settle, so the quiet start stops by itself. A block that is not
// in equilibrium slides within each quiet step from rest, as seed Eq. 4 has it over one step:
// ½ a Δt² a step with a = g (sin α − cos α tan φ) (the split impulses' trapezoidal move is exact
// for a steady force). The blocks of a landslide therefore creep before t = 0 by as many such
// slides as the quiet start runs steps, and a longer quiet start only moves them further from
// where they were given: the Vajont scene runs 250 (docs/vajont.md, "The quiet start's length").
// Swept over slopes, friction on both sides of them, steps and substeps, and lengths of 0 to 250.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

constexpr double kGravity = 9.81;  // m/s^2, verify/cases.cpp's scenes

struct QuietRun {
  int steps_run = 0;         // the quiet start's steps (SolverReport::quiet_start_steps)
  double change = 0.0;       // its last impulse change, of the largest
  double creep = 0.0;        // m: the measure point's move down the slope before t = 0
  double normal_move = 0.0;  // m: and across it (into the slope is negative)
  bool completed = false;
};

// seed §2.3's incline (verify/cases.hpp) at slope tan α = `ratio`, friction `phi`, steps of
// `step` s of `substeps` substeps, a quiet start of at most `length` steps; run for one step.
QuietRun run_incline(double ratio, double phi, double step, int substeps, int length) {
  verification::InclineSetup setup;
  setup.slope_ratio = ratio;
  setup.friction_angle = phi;
  setup.time_step = step;
  setup.duration = step;
  setup.output_interval = step;
  Scene scene = verification::incline_scene(setup);
  scene.options.integrator = Integrator::Substep;
  scene.options.substeps = substeps;
  scene.options.quiet_start_steps = length;
  const Vec2 given = scene.measure[0].at;
  const Vec2 along = Vec2(1.0, -ratio).normalized(), up(-along.y(), along.x());
  const SimulationResult r = simulate(scene);
  QuietRun out;
  out.completed = r.summary.status == RunStatus::Completed;
  out.steps_run = r.summary.solver.quiet_start_steps;
  out.change = r.summary.solver.quiet_start_change;
  if (r.history.empty()) return out;
  const HistoryRow& first = r.history.front();  // t = 0: where the quiet start left the point
  EXPECT_EQ(first.time, 0.0);
  const Vec2 moved = first.position - given;
  out.creep = moved.dot(along);
  out.normal_move = moved.dot(up);
  return out;
}

// The slide a block makes from rest over one step of `step` s (seed Eq. 4): ½ a Δt², a =
// g (sin α − cos α tan φ); none where friction holds it.
double one_step_slide(double ratio, double phi, double step) {
  const double alpha = std::atan(ratio);
  const double a = kGravity * (std::sin(alpha) - std::cos(alpha) * std::tan(phi * M_PI / 180.0));
  return a > 0.0 ? 0.5 * a * step * step : 0.0;
}

// A sliding block creeps before t = 0 by exactly the steps its quiet start ran, each one step's
// slide from rest (within 1 % and 1 um: the contact's slop lets the block settle a little into
// the slope as it takes up the weight, which is across the slope, not along it), and the quiet
// start never runs more steps than it is given. 0 steps: not a micrometre.
TEST(QuietStartLength, ASlidingBlockCreepsOneStepsSlideForEachQuietStep) {
  int runs = 0, ran_every_step = 0;
  double worst = 0.0;
  for (const double ratio : {0.5, 0.7, 1.0})          // α 26.6, 35.0, 45.0 deg
    for (const double phi : {10.0, 20.0})            // below every slope: it slides
      for (const double step : {0.005, 0.02})
        for (const int substeps : {1, 4})
          for (const int length : {0, 1, 5, 50, 250}) {
            const QuietRun r = run_incline(ratio, phi, step, substeps, length);
            std::ostringstream where;
            where << "tan alpha " << ratio << ", phi " << phi << ", step " << step << " x " << substeps
                  << ", quiet start of at most " << length << " steps";
            ASSERT_TRUE(r.completed) << where.str();
            EXPECT_LE(r.steps_run, length) << where.str();
            if (r.steps_run == length) ++ran_every_step;
            const double expected = r.steps_run * one_step_slide(ratio, phi, step);
            const double error = std::abs(r.creep - expected);
            EXPECT_LE(error, 0.01 * expected + 1e-6)
                << where.str() << ": crept " << r.creep << " m in " << r.steps_run << " quiet steps, expected "
                << expected << " m";
            if (length == 0) {
              EXPECT_EQ(r.creep, 0.0) << where.str();
            }
            worst = std::max(worst, expected > 0.0 ? error / expected : 0.0);
            ++runs;
          }
  std::cout << "[ quiet ] " << runs << " sliding runs, " << ran_every_step
            << " ran every step they were given; worst creep error " << worst << " of the expected\n";
}

// A block that friction holds (φ 5° above the slope) does not creep, whatever the length, and its
// quiet start stops by itself once its impulses settle (under 1e-4 of the largest), in fewer
// steps than it was given: a scene in equilibrium never pays for a long quiet start. Its contact
// taking up the weight, solved by sweeps, moves it along the slope by up to 10 um in all
// (9.5 um at 45 deg and 20 ms x 1; 2026-12-07), the same for 50 and 250 steps; a quiet step of
// the sliding blocks above moves them 0.015-1.1 mm. Bound: 20 um.
TEST(QuietStartLength, AHeldBlockDoesNotCreepAndSettlesByItself) {
  for (const double ratio : {0.5, 0.7, 1.0})
    for (const double step : {0.005, 0.02})
      for (const int substeps : {1, 4})
        for (const int length : {50, 250}) {
          const double phi = std::atan(ratio) * 180.0 / M_PI + 5.0;
          const QuietRun r = run_incline(ratio, phi, step, substeps, length);
          std::ostringstream where;
          where << "tan alpha " << ratio << ", phi " << phi << ", step " << step << " x " << substeps
                << ", quiet start of at most " << length << " steps";
          ASSERT_TRUE(r.completed) << where.str();
          EXPECT_LT(r.steps_run, length) << where.str() << ": change " << r.change;
          EXPECT_LE(r.change, 1e-4) << where.str();
          EXPECT_LE(std::abs(r.creep), 2e-5) << where.str() << ": crept " << r.creep << " m";
        }
}

}  // namespace
}  // namespace ddafit
