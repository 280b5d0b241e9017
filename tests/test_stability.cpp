// Scenes where DDA implementations are known to misbehave (field notes): a scene whose touching
// groups have no interface, huge steps, thin plates, columns. The standing masonry walls are in
// test_standing_walls.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <algorithm>
#include <string>
#include <vector>

#include "forward/io/scene_reader.hpp"
#include "forward/run_record.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"
#include "verify/verification.hpp"

namespace ddafit {
namespace {

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
  // The short-step warning is the user's only sign that a completed run is wrong (docs/theory.md,
  // Known limits (a)): with the default penalty, no run it spares may be inaccurate on the seed's
  // incline (seed Eq. 5) -- the displacement off by more than 1 %, or the acceleration curve (the
  // friction the block feels) by more than 2 % -- and the runs it spares stay within 1 % on both.
  // Since the sliding settle (model revision 2026-12-06.3 to .5) the incline holds down to 5 us
  // (0.003 of its elastic period; measured 0.0015 % / 0.0085 %). Since revision .06.6 the warning
  // comes below 3e-4 L/c, the shortest step checked (tests/test_landslide_blocks.cpp), so no run
  // of this map is warned, and none may be inaccurate.
  const auto map =
      verification::incline_stability_map({50.0}, {5e-6, 1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3});
  int warned = 0;
  for (const auto& p : map) {
    const bool inaccurate = !(p.displacement_error <= 0.01) || !(p.acceleration_error <= 0.02);
    if (inaccurate) {
      EXPECT_TRUE(p.warned) << "time step " << p.time_step << ": displacement error " << p.displacement_error
                            << ", acceleration error " << p.acceleration_error;
    }
    if (!p.warned) {
      EXPECT_LE(p.acceleration_error, 0.01) << "time step " << p.time_step;
    }
    warned += p.warned;
  }
  EXPECT_EQ(warned, 0) << "the warning comes below 3e-4 L/c = 0.48 us, under every step of the map";
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

// At steps of a third of a second and more the substep solver let the stack of five 1 m blocks
// through its ground and reported the run completed, the top block 122.6 m down after 5 s (free
// fall): 0.3 s x 1 and 1 s x 1 at revision 2026-12-05.9, 0.5 s x 1 and x 2 and 1 s x 1 at .05.8.
// The blocks fell before the clock ran: the quiet start's steps are the run's, its blocks as
// free, and a step of 0.3 s carries a block 0.9 m, nearly its own height, so one passed through
// the 1 m ground within a step and nothing looked (the containment check ran only in the run,
// and saw only a centroid inside a fixed block). From revision 2026-12-05.10 the check also runs
// after the quiet start, and it follows each free block's centroid along the straight line of
// its move (common/containment_check.hpp): a run either holds the stack or stops with a
// diagnosis. (Stopping a run once a free block lies wholly below every fixed block, tried first,
// also stopped 18 enabled tests whose blocks rightly end below their fixed ones.) Since revision
// 2026-12-06.2 a quiet start that turns a block by more than 0.01 rad, as a falling stack does, is
// done again at steps of 0.03 sqrt(L / |g|) (9.6 ms here): every run completes with the stack
// standing, its top within 5 mm.
TEST(Stability, AStackRunAtHugeStepsNeverFallsThroughItsGround) {
  const auto map = verification::substep_stability_map({0.3, 0.5, 1.0}, {1, 2});
  for (const auto& p : map)
    if (p.scene == "stack") {
      std::cout << "[measured] stack at " << p.time_step << " s x " << p.substeps << ": "
                << (p.completed ? "top moved " + std::to_string(p.error) + " m" : p.diagnosis) << "\n";
      EXPECT_TRUE(p.completed) << p.time_step << " s x " << p.substeps << ": " << p.diagnosis;
      if (p.completed) {
        EXPECT_LT(p.error, 0.005) << p.time_step << " s x " << p.substeps;
      }
    }
}

// The same event in the 100-brick wall (at 0.2-1 s x 1-2 its bottom course fell through the
// floor in the quiet start, found 2026-12-05): at steps of 0.1 to 1 s x 1, 2 and 4, every
// run holds the wall (its top within half a brick) or stops with a diagnosis naming the step.
TEST(Stability, AWallRunAtHugeStepsNeverFallsThroughItsFloor) {
  int stopped = 0;
  for (double step : {0.1, 0.2, 0.3, 0.5, 1.0})
    for (int n : {1, 2, 4}) {
      Scene scene = verification::brick_wall_scene(10, 10, 3.0);
      scene.max_step = step;
      scene.output_interval = step;
      scene.options.substeps = n;
      scene.options.integrator = Integrator::Substep;
      const SimulationResult r = simulate(scene);
      if (r.summary.status == RunStatus::Completed) {
        EXPECT_LT(r.summary.points[0].max_total_displacement, 0.25) << step << " s x " << n;
      } else {
        ++stopped;
        EXPECT_EQ(r.summary.status, RunStatus::Failed) << step << " s x " << n;
        EXPECT_NE(r.summary.message.find("time.step"), std::string::npos) << r.summary.message;
      }
    }
  std::cout << "[measured] wall at 0.1-1 s steps: " << stopped << " of 15 runs stopped with a diagnosis\n";
}

// A block fired at a thin fixed plate (no gravity, 10 ms steps, 20-500 m/s: up to five times its
// own length per step, plates of 0.1 and 0.5 m) never ends beyond it, with either solver: the
// speculative contacts and the step control stop it at the plate's face (the containment check
// of common/containment_check.hpp is the net behind them).
TEST(Stability, ABlockFiredAtAThinPlateNeverPassesIt) {
  for (Integrator integrator : {Integrator::Substep, Integrator::Implicit})
    for (double speed : {20.0, 100.0, 500.0})
      for (double thickness : {0.1, 0.5}) {
        Scene s = verification::collision_scene();
        s.duration = 0.2;
        s.max_step = 0.01;
        s.output_interval = 0.01;
        s.options.integrator = integrator;
        s.blocks[0].velocity = Vec2(speed, 0.0);
        s.blocks[1] = verification::block(
            "plate", {Vec2(1.5, -2), Vec2(1.5 + thickness, -2), Vec2(1.5 + thickness, 3), Vec2(1.5, 3)}, true);
        s.measure.resize(1);  // the striker's centre, 0.5 m from the plate's face
        const SimulationResult r = simulate(s);
        const std::string label = std::string(to_string(integrator)) + " at " + std::to_string(speed) + " m/s";
        if (r.summary.status != RunStatus::Completed) {
          EXPECT_NE(r.summary.message.find("time.step"), std::string::npos) << label << ": " << r.summary.message;
          continue;
        }
        // The striker's centre may reach 0.5 m on (its face on the plate's) plus an overlap.
        EXPECT_LT(r.summary.points[0].max_total_displacement, 0.51) << label;
      }
}


// verification::stack_scene with `count` square blocks of side `size` (m) on a ground 5 sizes
// wide, its measured point in the top block's middle.
Scene column_scene(double size, int count) {
  const double L = size;
  Scene s = verification::stack_scene();
  s.blocks[0].polygon = {Vec2(-2 * L, -L), Vec2(3 * L, -L), Vec2(3 * L, 0), Vec2(-2 * L, 0)};
  s.blocks.resize(1 + count);
  for (int k = 0; k < count; ++k)
    s.blocks[1 + k] = verification::block(
        std::string("b").append(std::to_string(k + 1)),  // GCC 12 -Wrestrict false positive on "b" + string
        {Vec2(0, k * L), Vec2(L, k * L), Vec2(L, (k + 1) * L), Vec2(0, (k + 1) * L)}, false);
  s.measure[0].at = Vec2(0.5 * L, (count - 0.5) * L);
  return s;
}

// Columns of 3 and 10 square blocks of 5 cm, 1 m and 20 m on a fixed ground, 2 s, at 1, 5 and 20 ms
// with 1 and 3 substeps and on the implicit solver. Every run either completes with the column
// standing (its top within 1 % of a block: measured at most 0.62 %, ten 1 m blocks at 20 ms x 1,
// where the column sways at up to 2 cm/s, the rocking column of docs/theory.md §13) or stops with
// a diagnosis naming the step; at 1 and 5 ms x 3 every substep run completes, and every implicit
// run. Found 2026-12-05: ten 5 cm cubes at 5 ms x 1 completed with the top moved 9 % of a block.
// Ten 5 cm cubes on the substep solver complete at 5 ms x 3, but not at every step near it (the
// known defect after this test).
TEST(Stability, AColumnStandsOrStopsWithADiagnosis) {
  int stopped = 0, runs = 0;
  double worst[2] = {0.0, 0.0};  // the top's largest move over the block's size, substep and implicit
  for (Integrator integrator : {Integrator::Substep, Integrator::Implicit})
    for (double size : {0.05, 1.0, 20.0})
      for (int count : {3, 10})
        for (double step : {0.001, 0.005, 0.02})
          for (int substeps : {1, 3}) {
            if (integrator == Integrator::Implicit && substeps > 1) continue;
            Scene s = column_scene(size, count);
            s.duration = 2.0;
            s.max_step = step;
            s.output_interval = std::max(0.05, step);
            s.options.substeps = substeps;
            s.options.integrator = integrator;
            const SimulationResult r = simulate(s);
            const std::string label = std::string(to_string(integrator)) + ", " + std::to_string(count) + " x " +
                                      std::to_string(size) + " m at " + std::to_string(step) + " s x " +
                                      std::to_string(substeps);
            ++runs;
            const bool must_complete = integrator == Integrator::Implicit || (substeps == 3 && step <= 0.005);
            if (r.summary.status != RunStatus::Completed) {
              ++stopped;
              EXPECT_FALSE(must_complete) << label << ": " << r.summary.message;
              EXPECT_NE(r.summary.message.find("time.step"), std::string::npos) << label << ": " << r.summary.message;
              continue;
            }
            EXPECT_LT(r.summary.points[0].max_total_displacement, 0.01 * size) << label;
            double& w = worst[integrator == Integrator::Implicit];
            w = std::max(w, r.summary.points[0].max_total_displacement / size);
          }
  std::cout << "[measured] columns: " << stopped << " of " << runs << " runs stopped with a diagnosis; the top moved "
            << worst[0] << " of a block at most (substep), " << worst[1] << " (implicit)\n";
}

// KNOWN DEFECT (the rocking column of docs/theory.md §13, found as a class 2026-12-06, revision
// 2026-12-05.12): a column of ten 5 cm cubes on the substep solver at 2-10 ms x 3 sways until the
// energy audit stops it: over 4 s it stopped at 3, 4, 6, 7 and 10 ms and stood at 2, 5 and 8 ms
// (within 0.23 % of a block). It must complete standing (its top within 1 % of a block, the class
// test's bound) at every step.
TEST(Stability, DISABLED_AColumnOfTenFiveCentimetreCubesStandsAtEveryStepSubstep) {
  for (double step : {0.002, 0.003, 0.004, 0.005, 0.006, 0.008, 0.01}) {
    const double L = 0.05;
    Scene s = column_scene(L, 10);
    s.duration = 4.0;
    s.max_step = step;
    s.output_interval = 0.05;
    s.options.substeps = 3;
    s.options.integrator = Integrator::Substep;
    const SimulationResult r = simulate(s);
    EXPECT_EQ(r.summary.status, RunStatus::Completed) << step << " s: " << r.summary.message;
    if (r.summary.status != RunStatus::Completed) continue;
    EXPECT_LT(r.summary.points[0].max_total_displacement, 0.01 * L) << step << " s";
  }
}

// Tall columns: 10, 20 and 30 square blocks of 0.5, 1, 2, 5 and 10 m on a fixed ground, 4 s,
// at 2, 5, 10 and 20 ms (the substep solver with 3 and 4 substeps). A run either completes with
// the column standing, its top within 1 % of a block sideways, or stops with a diagnosis naming
// the step. Returns the runs that do neither, and the largest sideways move of a completed run.
struct TallColumns {
  int runs = 0, off = 0;
  double worst = 0.0;  // of a block
  std::string worst_label;
};
TallColumns sweep_tall_columns(Integrator integrator) {
  TallColumns c;
  for (double size : {0.5, 1.0, 2.0, 5.0, 10.0})
    for (int count : {10, 20, 30})
      for (double step : {0.002, 0.005, 0.01, 0.02})
        for (int substeps : {3, 4}) {
          if (integrator == Integrator::Implicit && substeps != 3) continue;
          Scene s = column_scene(size, count);
          s.duration = 4.0, s.max_step = step, s.output_interval = 0.05;
          s.options.substeps = substeps;
          s.options.integrator = integrator;
          const SimulationResult r = simulate(s);
          const std::string label = std::to_string(count) + " x " + std::to_string(size) + " m at " +
                                    std::to_string(step) + " s x " + std::to_string(substeps);
          ++c.runs;
          if (r.summary.status != RunStatus::Completed) {
            if (r.summary.message.find("time.step") == std::string::npos) ++c.off;
            continue;
          }
          const double sideways = r.summary.points[0].max_lateral_displacement / size;
          if (sideways >= 0.01) ++c.off;
          if (sideways > c.worst) c.worst = sideways, c.worst_label = label;
        }
  return c;
}

// The implicit solver, which solves a step's contacts together, holds every tall column: 60 runs,
// each completed, the top at most 2.5e-5 of a block sideways (measured 2026-12-06, revision
// 2026-12-06.14: 30 x 5 m at 10 ms).
TEST(Stability, TallColumnsStandImplicit) {
  const TallColumns c = sweep_tall_columns(Integrator::Implicit);
  EXPECT_EQ(c.runs, 60);
  EXPECT_EQ(c.off, 0);
  EXPECT_LT(c.worst, 1e-4) << c.worst_label;
  std::cout << "[measured] tall columns, implicit: top at most " << c.worst << " of a block sideways (" << c.worst_label
            << ")\n";
}

// KNOWN DEFECT (found 2026-12-06 by a black-box sweep, revision 2026-12-06.14; docs/theory.md §13,
// "Tall columns"): the substep solver lets 44 of these 120 columns sway: 30 complete with the top
// more than 1 % of a block sideways (up to 106 % at 30 x 0.5 m, 20 ms x 3), 14 sway until the
// energy audit stops them with its diagnosis. Of the 40 columns of ten, 39 stand (one stops). Traced: each manifold's
// passes take its two points in turn and stop at 1 % of its impulse, so the corners of a joint
// carry unequal shares and every block turns the same way; two sweeps a substep do not converge
// a column of twenty and its sway grows. Solving the manifolds of small islands at rest to 1e-5
// with 12 more sweeps left 6 of 120 off, but changed what a heavy block landing on a row of
// resting cubes does (a cube moved 17 mm, bound 5 mm) and how a row struck against a wall
// rebounds; not kept.
TEST(Stability, DISABLED_TallColumnsStandOrStopWithADiagnosisSubstep) {
  const TallColumns c = sweep_tall_columns(Integrator::Substep);
  EXPECT_EQ(c.runs, 120);
  EXPECT_EQ(c.off, 0) << "worst " << c.worst << " of a block (" << c.worst_label << ")";
}

// A block dropped flat onto a fixed floor stays down (DDA's contacts are perfectly plastic): blocks
// of 0.1, 1 and 10 m dropped from 0.1, 1 and 5 times their size, at 1, 5, 10 and 20 ms (three
// substeps), both solvers, 72 runs. After the landing its base never rises more than 1e-3 of its
// size above the floor, it ends at rest (under 1 mm/s) and overlaps under 1 %. Measured
// (2026-12-05, revision .12.05.12): the base at most 9.7e-5 of the size above the floor (implicit,
// the 10 m block at 20 ms), end speeds under 1.3e-5 m/s, overlaps under 0.11 %.
TEST(Stability, ABlockDroppedOnTheFloorStaysDown) {
  double worst_rise = -1.0;
  for (Integrator integrator : {Integrator::Substep, Integrator::Implicit})
    for (double L : {0.1, 1.0, 10.0})
      for (double h : {0.1, 1.0, 5.0})
        for (double step : {0.001, 0.005, 0.01, 0.02}) {
          Scene s = verification::stack_scene();
          s.blocks.resize(2);
          s.blocks[0].polygon = {Vec2(-5 * L, -L), Vec2(6 * L, -L), Vec2(6 * L, 0), Vec2(-5 * L, 0)};
          const double y0 = h * L;
          s.blocks[1] = verification::block("b1", {Vec2(0, y0), Vec2(L, y0), Vec2(L, y0 + L), Vec2(0, y0 + L)}, false);
          s.measure[0].at = Vec2(0.5 * L, y0 + 0.5 * L);
          const double fall = std::sqrt(2.0 * h * L / 9.81);
          s.duration = fall + 1.0 + std::sqrt(L);
          s.max_step = step;
          s.output_interval = 0.01;
          s.options.substeps = 3;
          s.options.integrator = integrator;
          double rise = -1e300, speed = 0.0;
          SimulationHooks hooks;
          hooks.on_output = [&](double time, const BlockSystem& system) {
            if (time > fall + 0.05) rise = std::max(rise, system.blocks[1].centroid.y() - 0.5 * L);
            speed = system.blocks[1].velocity.head<2>().norm();
          };
          const SimulationResult r = simulate(s, hooks);
          const std::string label = std::string(to_string(integrator)) + ", " + std::to_string(L) + " m block from " +
                                    std::to_string(h) + " sizes at " + std::to_string(step) + " s";
          ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
          EXPECT_LT(rise, 1e-3 * L) << label << ": bounced";
          EXPECT_LT(speed, 1e-3) << label << ": still moving at the end";
          EXPECT_LT(r.summary.solver.worst_penetration_ratio, kOverlapBoundRatio) << label;
          worst_rise = std::max(worst_rise, rise / L);
        }
  std::cout << "[measured] dropped blocks: the base at most " << worst_rise << " of the size above the floor\n";
}

}  // namespace
}  // namespace ddafit
