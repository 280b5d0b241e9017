// Scenes where DDA implementations are known to misbehave (field notes): a standing
// masonry wall, whose many nearly unloaded corner contacts make the open-close
// iteration cycle, and a scene whose touching groups have no interface.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "forward/io/scene_reader.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"
#include "verify/verification.hpp"

namespace ddafit {
namespace {

class BrickWall : public ::testing::TestWithParam<Integrator> {};

TEST_P(BrickWall, StandsStill) {
  // 100 bricks in running bond, 35 deg joints, 0.5 s, with each solver. In equilibrium
  // only the contacts settle: the top course may move by elastic shortening and contact
  // compression of ten courses (micrometres: 9 um implicit, 24 um substep), not by
  // sliding or rocking. 0.1 mm is four to ten times the settling measured and far below
  // any real movement (a 0.5 m brick).
  Scene scene = verification::brick_wall_scene(10, 10, 0.5);
  scene.options.integrator = GetParam();
  const SimulationResult r = simulate(scene);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  EXPECT_LT(r.summary.points[0].max_total_displacement, 1e-4);
  EXPECT_LT(r.summary.points[0].peak_total_velocity, 1e-2);  // nothing is thrown about
}

INSTANTIATE_TEST_SUITE_P(Stability, BrickWall, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return to_string(info.param); });

// A standing wall has no collisions: its courses settle at a few cm/s, faster than gravity
// gives in a 1 ms step, and from revision 2026-11-28.4 to .29.4 the implicit solver took those
// settling groups for impacts and set their bed joints sliding; the open-close iteration could
// not settle them in 8 passes and cut the step (the 1621-block wall of cases/walls: 1 cut in
// its first 10 ms, 20 in 150 ms on bench/peer's wall). A step cut there is a defect, not
// caution: nothing moves. Walls of 100 to 1620 bricks, the first 10 ms at 1 ms.
class StandingWallImplicit : public ::testing::TestWithParam<int> {};

TEST_P(StandingWallImplicit, NeedsNoStepCut) {
  const int size = GetParam();
  Scene scene = size == 0 ? io::read_scene(std::string(DDAFIT_CASES_DIR) + "/walls/brick_wall_1621.yaml")
                          : verification::brick_wall_scene(size, size, 0.01);
  scene.options.integrator = Integrator::Implicit;
  scene.duration = 0.01;
  scene.max_step = 0.001;
  const SimulationResult r = simulate(scene);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  std::cout << "[measured] wall " << (size == 0 ? std::string("cases/walls 1621") : std::to_string(size * size))
            << ": " << r.summary.run.steps << " steps, " << r.summary.run.step_cuts << " cuts, "
            << r.summary.run.open_close_iterations << " passes\n";
  EXPECT_EQ(r.summary.run.step_cuts, 0);
}

INSTANTIATE_TEST_SUITE_P(Stability, StandingWallImplicit, ::testing::Values(10, 20, 30, 0),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return info.param == 0 ? std::string("bricks1620") : "bricks" + std::to_string(info.param * info.param);
                         });

TEST(Stability, ReusedFactorSolvesTheSameWall) {
  // control.reuse_factorization solves passes by CG on an older factor down to a residual
  // of 1e-10 |F|. On the standing wall (100 bricks, few contact changes once settled) it
  // must take over some passes and leave the answer where the direct solve puts it:
  // the same settling to within 1 % of its micrometres (chaotic contact histories could
  // differ more, but this wall does not slide).
  Scene direct = verification::brick_wall_scene(10, 10, 0.5);
  direct.options.integrator = Integrator::Implicit;  // the factorisation is the implicit solver's
  Scene reused = direct;
  reused.options.reuse_factorization = true;
  const SimulationResult a = simulate(direct), b = simulate(reused);
  ASSERT_EQ(a.summary.status, RunStatus::Completed) << a.summary.message;
  ASSERT_EQ(b.summary.status, RunStatus::Completed) << b.summary.message;
  EXPECT_GT(b.summary.run.cg_solves, 0);
  EXPECT_EQ(a.summary.run.cg_solves, 0);
  const double da = a.summary.points[0].max_total_displacement, db = b.summary.points[0].max_total_displacement;
  EXPECT_NEAR(db, da, 0.01 * da);
}

TEST(Stability, TouchingGroupsWithoutInterfaceAreReportedAtStart) {
  // Two interfaces, no default and no rule for the pair that touches at t = 0: the run
  // must refuse (exit code 2 in the CLI), not read a missing interface.
  Scene s = verification::stack_scene();
  Interface other;
  other.name = "other";
  other.friction_angle = 20.0;
  s.interfaces.push_back(other);
  s.default_interface = -1;
  const SimulationResult r = simulate(s);
  EXPECT_EQ(r.summary.status, RunStatus::InvalidScene);
  EXPECT_NE(r.summary.message.find("no interface"), std::string::npos) << r.summary.message;
}

TEST(Stability, TimeStepWarningMarksTheInaccurateRuns) {
  // With the default penalty, the runs that miss the incline's analytic curve (seed Eq. 5)
  // are exactly those that carry the short-time-step warning: the warning is the user's
  // only sign that a completed run is wrong (docs/verification.md). Inaccurate: the
  // displacement off by more than 1 %, or the acceleration curve (the friction the block
  // feels) by more than 2 % -- at 0.2 ms the spurious vibration lowers the friction by
  // 7 % while the displacement is still within 1 %. Accurate runs stay within 1 % on both.
  const auto map = verification::incline_stability_map({50.0}, {1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3});
  for (const auto& p : map) {
    const bool inaccurate = !(p.displacement_error <= 0.01) || !(p.acceleration_error <= 0.02);
    EXPECT_EQ(p.warned, inaccurate) << "time step " << p.time_step << ": displacement error "
                                    << p.displacement_error << ", acceleration error " << p.acceleration_error;
    if (!p.warned) {
      EXPECT_LE(p.acceleration_error, 0.01) << "time step " << p.time_step;
    }
  }
}

TEST(Stability, SubstepSolverFailsWithADiagnosisNeverWithGarbage) {
  // The substep solver's stability map (docs/verification.md): the incline and a stack of
  // five 1 m blocks at rest, up to 50 ms steps. Every run either completes with a finite
  // result or stops with a message naming the settings to change; at the scene's 1 ms both
  // scenes hold their verification tolerances (incline 0.5 %, stack 1 mm).
  const auto map = verification::substep_stability_map({1e-3, 5e-2}, {2, 4});
  ASSERT_EQ(map.size(), 8u);
  const verification::SubstepStabilityPoint* coarse_stack = nullptr;
  for (const auto& p : map) {
    if (p.completed) {
      EXPECT_TRUE(std::isfinite(p.error)) << p.scene << " at " << p.time_step << " s";
    } else {
      EXPECT_NE(p.diagnosis.find("time.substeps"), std::string::npos) << p.diagnosis;
      EXPECT_NE(p.diagnosis.find("step"), std::string::npos) << p.diagnosis;
    }
    if (p.time_step == 1e-3) {
      EXPECT_TRUE(p.completed) << p.scene << ": " << p.diagnosis;
      EXPECT_LT(p.error, p.scene == "incline" ? 0.005 : 1e-3) << p.scene;
    }
    if (p.scene == "stack" && p.time_step == 5e-2 && p.substeps == 2) coarse_stack = &p;
  }
  // 50 ms x 2 (25 ms substeps on 1 m blocks), the map's one failure until model revision
  // 2026-12-05.9 (the energy audit stopped it at t = 3.1 s), holds the stack within the 1 mm of
  // the scene's own step since overlaps in a scene this small are corrected from 2.5e-4 of a
  // block (control.deep_overlap_ratio; measured 0.57 mm). Until revision 2026-12-03.6 the stack
  // failed at every step from 20 ms and at 50 ms x 4 too: the step control cut its steps below
  // the quiet start's and the warm start handed on the larger steps' impulses unscaled
  // (docs/theory.md §13, the warm start).
  ASSERT_NE(coarse_stack, nullptr);
  ASSERT_TRUE(coarse_stack->completed) << coarse_stack->diagnosis;
  EXPECT_LT(coarse_stack->error, 1e-3) << "stack at 50 ms x 2";
}

// KNOWN DEFECT (found 2026-12-05 at revision 2026-12-05.9, and there at .05.8): at steps of a
// third of a second and more the substep solver can let the stack of five 1 m blocks through
// its ground and report the run completed, the top block 122.6 m down after 5 s (free fall):
// 0.3 s x 1 and 1 s x 1 at .05.9; 0.5 s x 1 and x 2 and 1 s x 1 at .05.8 (0.5 s x 1 at .05.9
// stops with an overlap diagnosis). Nothing checks for a block that has passed wholly through a
// fixed one (common/containment_check.hpp catches only a centroid inside one). A completed run
// must not have moved the stack's top by more than a block. Tried and withdrawn (2026-12-05):
// stopping a run once a free block lies wholly below every fixed block stopped five of these
// six stack runs with a diagnosis (0.3 s x 2 completes within 1.4 mm), and 18 enabled tests of
// both solvers (three command-line tests failed too) whose blocks rightly end below their fixed
// ones (a block off a corner, chains hung by bonds, a kinked surface, an incline's sliders).
TEST(Stability, DISABLED_AStackRunAtHugeStepsNeverFallsThroughItsGround) {
  const auto map = verification::substep_stability_map({0.3, 0.5, 1.0}, {1, 2});
  for (const auto& p : map)
    if (p.scene == "stack" && p.completed) {
      EXPECT_LT(p.error, 1.0) << p.time_step << " s x " << p.substeps;
    }
}

}  // namespace
}  // namespace ddafit
