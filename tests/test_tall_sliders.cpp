// Tall sliders across flush joints: a block sliding at friction angle phi carries its base
// reaction at r = tan(phi) H / L of its half-length ahead of its centre (the friction at the
// base turns it forward; r = 1 is where it would topple rather than slide). The sweeps of
// test_joint_crossing.cpp reach r of about 0.8 with sliders no taller than long; a tall block
// near its friction angle, the commonest block of a steep jointed slope, puts nearly all its
// weight on its front corner, and that corner meets every joint first. Here r = 0.8, 0.9 and
// 0.95, slopes of 20-40 deg at 1 deg steeper than the friction, sliders 0.3 and 3 m long over
// joints every 0.1, 0.3 and 1.0 of their length, from rest and at 3 m/s, each on the slope
// descending to the right and on its mirror image (forward/mirror.hpp): 216 runs a solver, to
// test_joint_crossing.cpp's tolerance (1 % of seed Eq. 4 wherever the slider has moved 1 cm).
#include <cmath>
#include <iostream>
#include <string>

#include "forward/common/known_limits.hpp"
#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

struct TallSweep {
  int runs = 0, off = 0;
  double worst = 0.0;
  std::string worst_label;
};

// The class above, each run held to seed Eq. 4 by expect_crossing_at_step (slope_scene.hpp);
// counts the runs off by more than 1 %.
TallSweep sweep_tall_sliders(Integrator integrator) {
  TallSweep sweep;
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : {0.8, 0.9, 0.95})
        for (const double length : {0.3, 3.0})
          for (const double spacing : {0.1, 0.3, 1.0})
            for (const double speed : {0.0, 3.0}) {
              Crossing c;
              c.slope = slope, c.friction = slope - 1.0, c.length = length;
              c.height = r * length / std::tan(c.friction * kDegree);
              c.spacing = spacing * length, c.speed = speed, c.front_gap = 0.02 * c.spacing;
              std::string label;
              const double error = expect_crossing_at_step(c, integrator, kStep, mirrored, label);
              ++sweep.runs;
              if (error >= kDisplacementTolerance) ++sweep.off;
              if (error > sweep.worst) sweep.worst = error, sweep.worst_label = label + ", r " + std::to_string(r);
            }
  return sweep;
}

// Measured 2026-12-04 (revision 2026-12-04.1): worst 1.3e-4 of Eq. 4 over the 216 runs.
TEST(TallSliders, TallSlidersCrossFlushJointsAsSeedEq4SaysSubstep) {
  const TallSweep sweep = sweep_tall_sliders(Integrator::Substep);
  EXPECT_EQ(sweep.runs, 216);
  std::cout << "[measured] " << sweep.runs << " tall sliders, substep: worst displacement error " << sweep.worst
            << " (" << sweep.worst_label << ")\n";
}

// KNOWN DEFECT (found 2026-12-04 by a black-box sweep through `ddafit simulate`): the implicit
// solver, which `time.integrator: auto` picks for scenes of under 100 free blocks, takes 58 of
// these 216 runs more than 1 % off seed Eq. 4 (revision 2026-12-04.1; 52 since the sliding settle of
// revision 2026-12-06.3, forward/step/settle_sliding.hpp, worst 70 %; 44 since the impulses'
// momentum velocity of .14, forward/mass_matrix.hpp, worst 64 %; 42 since the both-ways sliding settle
// of .15, forward/step/settle_sliding.cpp: the two 3 m sliders on 20 deg at r 0.8; 24 since a last pass
// whose normal forces still move goes on, .20, forward/step/open_close_iterate.cpp, worst 3.9 %).
// At .12: 26 are 0.3 m sliders,
// 20 of them over joints every 0.03 m: worst 70 % off from rest (r 0.9, 40 deg), 28 % at
// 3 m/s. 32 are 3 m sliders from rest, worst 3.9 % at the first centimetre, over one joint per
// slider length as over ten: a kick in the first steps that does not decay. None of the 3 m
// sliders at 3 m/s is off. Traced on probe scenes of the same class (docs/theory.md §5, "Known
// limits", (h)): the rear points carry under a twentieth of the front's load, a penetration
// below the contact tolerance, so the slider rests on its front corner alone and rocks at the
// step's Nyquist frequency, which the time integration does not damp (v1 = 2 D / dt - v0);
// points that cycle between open and closed are frozen closed in tension (glue up to penalty
// x tolerance), which raises the compression, and so the friction, at the front; a corner
// handed from one block to the next across a joint starts without friction; and the
// open-close iteration's stall test accepts a normal force still halving from pass to pass.
// Mending these one at a time or together (tried, not kept) left 10-21 of 72 probe runs off.
// The substep solver runs the whole class (above).
TEST(TallSliders, DISABLED_TallSlidersCrossFlushJointsAsSeedEq4SaysImplicit) {
  const TallSweep sweep = sweep_tall_sliders(Integrator::Implicit);
  EXPECT_EQ(sweep.runs, 216);
  std::cout << "[measured] " << sweep.runs << " tall sliders, implicit: " << sweep.off
            << " off by more than 1 %, worst " << sweep.worst << " (" << sweep.worst_label << ")\n";
}

// A slider of the class above at `r`, on `slope` with friction `friction` (deg), 0.3 m long
// over joints every 0.03 m, as built or mirrored.
Scene tall_slider_scene(double slope, double friction, double r, bool mirrored, Integrator integrator,
                        double speed = 0.0) {
  Crossing c;
  c.slope = slope, c.friction = friction, c.length = 0.3, c.speed = speed;
  c.height = r * c.length / std::tan(c.friction * kDegree);
  c.spacing = 0.1 * c.length, c.front_gap = 0.02 * c.spacing;
  Scene scene = crossing_scene(c, integrator);
  scene.duration = 0.01;  // the warning is decided at t = 0
  return mirrored ? mirrored_scene(scene) : scene;
}

// find_known_limits finds the class at t = 0 (forward/common/known_limits.hpp): the slider built with
// r = tan(phi) H / L and its slope, to rounding (1e-9), both ways down; none where the face is
// gentler than its friction (the block is held from rest) however tall the block.
TEST(TallSliders, TheClassIsFoundAtTheStartFromTheSlidersShape) {
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : {0.3, 0.8, 0.95}) {
        const Scene scene = tall_slider_scene(slope, slope - 1.0, r, mirrored, Integrator::Implicit);
        const BlockSystem s = build_block_system(scene);
        const TallSlider found = find_known_limits(scene, s).slider;
        ASSERT_GE(found.block, 0) << slope << " deg, r " << r;
        EXPECT_EQ(s.block_names[found.block], "slider");
        EXPECT_NEAR(found.reach, r, 1e-9 * r) << slope << " deg, r " << r << (mirrored ? ", mirrored" : "");
        EXPECT_NEAR(found.slope, slope, 1e-9 * slope);
        EXPECT_DOUBLE_EQ(found.friction, slope - 1.0);
      }
  const Scene held = tall_slider_scene(30.0, 35.0, 0.95, false, Integrator::Implicit);
  EXPECT_LT(find_known_limits(held, build_block_system(held)).slider.block, 0);
  // Given 3 m/s down a face its friction would hold from rest: found, as launched.
  const Scene thrown = tall_slider_scene(30.0, 35.0, 0.95, false, Integrator::Implicit, 3.0);
  const TallSlider found = find_known_limits(thrown, build_block_system(thrown)).slider;
  EXPECT_NEAR(found.reach, 0.95, 1e-9);
  EXPECT_TRUE(found.launched);
}

// Until the implicit solver runs the class, it says so (docs/theory.md, known limits (i)): one
// warning naming the slider for each run of the class beyond r = 0.8 (0.85: 12-17 % off seed
// Eq. 4, 0.9: up to 70 %), both ways down, and none at r = 0.5 and 0.8 (within 1 %), where the
// face is gentler than the friction, or on the substep solver (within 1.3e-4).
TEST(TallSliders, TheImplicitSolverWarnsOfTheTallSlidersItRunsOffEq4) {
  const auto warnings = [](double slope, double friction, double r, bool mirrored, Integrator integrator) {
    const SimulationResult run = simulate(tall_slider_scene(slope, friction, r, mirrored, integrator));
    EXPECT_EQ(run.summary.status, RunStatus::Completed) << run.summary.message;
    return run.summary.warnings;
  };
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0}) {
      for (const double r : {0.85, 0.9, 0.95}) {
        const std::vector<std::string> w = warnings(slope, slope - 1.0, r, mirrored, Integrator::Implicit);
        ASSERT_EQ(w.size(), 1u) << slope << " deg, r " << r;
        EXPECT_NE(w[0].find("block 'slider'"), std::string::npos) << w[0];
        EXPECT_NE(w[0].find("known limits (i)"), std::string::npos) << w[0];
        EXPECT_TRUE(warnings(slope, slope - 1.0, r, mirrored, Integrator::Substep).empty());
      }
      for (const double r : {0.5, 0.8}) EXPECT_TRUE(warnings(slope, slope - 1.0, r, mirrored, Integrator::Implicit).empty());
      EXPECT_TRUE(warnings(slope, slope + 5.0, 0.95, mirrored, Integrator::Implicit).empty());
      // Given 3 m/s on that gentler face it slides until its friction stops it: warned.
      const SimulationResult thrown =
          simulate(tall_slider_scene(slope, slope + 5.0, 0.95, mirrored, Integrator::Implicit, 3.0));
      ASSERT_EQ(thrown.summary.warnings.size(), 1u);
      EXPECT_NE(thrown.summary.warnings[0].find("is given a velocity along"), std::string::npos);
    }
}

// time.integrator: auto (the default) runs a scene of the class on the substep solver, though it
// has under 100 free blocks, and says why in solver.reason; below r = 0.8 it keeps the implicit
// solver. From rest and at 3 m/s on faces 1 deg steeper than the friction, and at 3 m/s on faces
// 5 deg gentler (sliding to a stop: 11-51 % off on the implicit solver at r 0.9-0.95), both ways
// down, to the class's tolerance (1 % of seed Eq. 4 wherever the slider has moved 1 cm): 54 runs
// of the class, and 12 at r = 0.5 kept on the implicit solver.
TEST(TallSliders, AutoRunsTallSlidersOnTheSubstepSolver) {
  int tall = 0, squat = 0;
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : {0.5, 0.85, 0.9, 0.95})
        for (const auto& [speed, excess] : {std::pair{0.0, 1.0}, std::pair{3.0, 1.0}, std::pair{3.0, -5.0}}) {
          if (r == 0.5 && speed > 0.0 && excess > 0.0) continue;
          Crossing c;
          c.slope = slope, c.friction = slope - excess, c.length = 0.3, c.speed = speed;
          c.height = r * c.length / std::tan(c.friction * kDegree);
          c.spacing = 0.1 * c.length, c.front_gap = 0.02 * c.spacing;
          Scene scene = crossing_scene(c, Integrator::Auto);
          if (mirrored) scene = mirrored_scene(scene);
          SimulationResult run = simulate(scene);
          if (mirrored) unmirror_history(run.history);
          const std::string label = describe(c, Integrator::Auto) + ", r " + std::to_string(r) +
                                    (mirrored ? ", descending to the left" : "");
          ASSERT_EQ(run.summary.status, RunStatus::Completed) << label << ": " << run.summary.message;
          if (r > kTallSliderReach) {
            ++tall;
            EXPECT_EQ(run.summary.solver.integrator, Integrator::Substep) << label;
            EXPECT_NE(run.summary.solver.reason.find("tall slider"), std::string::npos) << run.summary.solver.reason;
          } else {
            ++squat;
            EXPECT_EQ(run.summary.solver.integrator, Integrator::Implicit) << label;
          }
          double when = 0.0;
          EXPECT_LT(displacement_error(run, c, &when), kDisplacementTolerance) << label << ": worst at t = " << when;
        }
  EXPECT_EQ(tall, 54);
  EXPECT_EQ(squat, 12);
}

}  // namespace
}  // namespace ddafit
