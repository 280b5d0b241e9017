// A heavy block sliding over a row of much lighter free blocks: a 0.3 m slider on blocks of a
// tenth, three tenths and the whole of its length (half as thick as long, so that each stands
// by itself), which rest on a fixed plane and are held to it and to each other at 75 deg; the
// slider 1 deg steeper than its friction on the row, at r = tan(phi) H / L = 0.5 to 0.95 (the
// share of its half-length ahead of its centre at which its base reaction acts), on slopes of
// 20-40 deg descending to the right and on their mirror images (forward/mirror.hpp). The
// slider is 120-550 times as heavy as a 3 cm row block, 14-60 times a 9 cm one, 1-6 times a
// 0.3 m one. Tolerances of
// test_joint_crossing.cpp: 1 % of seed Eq. 4 wherever the slider has moved 1 cm (a hooked
// slider falls 10-100 % behind), and overlaps under 1 % of the smaller block; the row in place
// within 1 mm (test_free_row.cpp: its elastic settling is micrometres).
//
// Found 2026-12-05 by a sweep of tall sliders (test_tall_sliders.cpp) moved onto free rows.
// Gauss-Seidel hands a light block's support about m_light / m_heavy of a heavy block's load
// per sweep (forward/substep/converge_heavy.hpp); where the slider's weight sits on its front
// corner (r near 1), the light block under it sinks, the slider tilts onto it, lifts its rear
// and rocks to a stop. Probes (not kept) in docs/theory.md, Known limits (j).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "forward/common/known_limits.hpp"
#include "forward/mirror.hpp"
#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

constexpr double kRowMovement = 1e-3;  // m, as test_free_row.cpp
constexpr double kSliderLength = 0.3;  // m
constexpr double kDuration1 = 1.0;     // s: a slider 1 deg steeper than its friction moves 8-11 cm from rest

struct LightRow {
  double slope = 30.0, r = 0.5;
  double row_share = 0.1;  // the row blocks' length, of the slider's
  double speed = 0.0;      // m/s down the slope at t = 0
  bool mirrored = false;
  double step = kStep;     // time.step, s
  double deep_overlap_ratio = 0.0;  // control.deep_overlap_ratio (0: automatic)
};

struct LightRowRun {
  SimulationResult result;
  double error = 0.0, when = 0.0;  // against seed Eq. 4
  double row_moved = 0.0;          // m
  int row_blocks = 0;
  std::string label;
};

// The scene of the class above, at duration kDuration1 (as built; the run mirrors it); the
// row blocks are blocks 1..row_blocks (block 0 the plane), the slider the last.
Scene light_row_scene(const LightRow& c, Integrator integrator, int& row_blocks) {
  const double friction = c.slope - 1.0;
  const double height = c.r * kSliderLength / std::tan(friction * kDegree);
  const double row_length = c.row_share * kSliderLength, row_height = 0.5 * row_length;
  const double a = eq4_acceleration(c.slope, friction);
  const double travel = 1.3 * (c.speed * kDuration1 + 0.5 * a * kDuration1 * kDuration1) + 0.1 * kSliderLength;
  int k = 1;  // the slider's front 2 % of a row block before a joint
  while (k * row_length - 0.02 * row_length - kSliderLength < 0.2 * kSliderLength) ++k;
  const double rear = k * row_length - 0.02 * row_length - kSliderLength;
  row_blocks = static_cast<int>(std::ceil((rear + 1.5 * kSliderLength + travel) / row_length));
  Scene s = base_scene(kDuration1, c.step, kOutput, integrator);
  s.options.deep_overlap_ratio = c.deep_overlap_ratio;
  const int holds = add_interface(s, "holds", 75.0);
  const int slides = add_interface(s, "slides", friction);
  s.contact_rules = {{"plane", "row", holds}, {"row", "row", holds}, {"slider", "row", slides}};
  s.default_interface = slides;
  const Slope slope(c.slope);
  add_plane_and_free_row(s, slope, row_blocks * row_length + 0.1, row_length, row_height, row_blocks);
  BlockInput slider = block("slider", box(slope.at(rear, row_height), slope.along, slope.up, kSliderLength, height),
                            false, 0, "slider");
  slider.velocity = c.speed * slope.along;
  s.blocks.push_back(slider);
  s.measure.push_back({"centre", slope.at(rear + 0.5 * kSliderLength, row_height + 0.5 * height)});
  return s;
}

// The slider's mass over a row block's (one material): (L H) / (l l / 2).
double light_row_mass_ratio(const LightRow& c) {
  const double height = c.r * kSliderLength / std::tan((c.slope - 1.0) * kDegree);
  const double row_length = c.row_share * kSliderLength;
  return kSliderLength * height / (0.5 * row_length * row_length);
}

LightRowRun run_light_row(const LightRow& c, Integrator integrator) {
  LightRowRun run;
  const Scene s = light_row_scene(c, integrator, run.row_blocks);
  run.result = run_watching_row(s, run.row_blocks, c.mirrored, run.row_moved);
  Crossing eq4;
  eq4.slope = c.slope, eq4.friction = c.slope - 1.0, eq4.speed = c.speed;
  run.error = run.result.summary.status == RunStatus::Completed ? displacement_error(run.result, eq4, &run.when) : 1.0;
  run.label = name_of(integrator) + ": slope " + std::to_string(c.slope) + " deg, r " + std::to_string(c.r) +
              ", row blocks " + std::to_string(c.row_share * kSliderLength) + " m (" + std::to_string(run.row_blocks) +
              "), v0 " + std::to_string(c.speed) + " m/s" + (c.mirrored ? ", mirrored" : "");
  return run;
}

bool within(const LightRowRun& run) {
  return run.result.summary.status == RunStatus::Completed && run.error < kDisplacementTolerance &&
         run.row_moved < kRowMovement && run.result.summary.solver.worst_penetration_ratio < kMaxPenetrationRatio;
}

struct LightRowSweep {
  int runs = 0, off = 0;
  double worst = 0.0;
  std::string worst_label;
};

LightRowSweep sweep_light_rows(Integrator integrator, const std::vector<double>& ratios,
                               const std::vector<double>& speeds, double step = kStep) {
  LightRowSweep sweep;
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : ratios)
        for (const double row_share : {0.1, 0.3, 1.0})
          for (const double speed : speeds) {
            const LightRowRun run = run_light_row({slope, r, row_share, speed, mirrored, step}, integrator);
            ++sweep.runs;
            if (!within(run)) ++sweep.off;
            if (run.error > sweep.worst) sweep.worst = run.error, sweep.worst_label = run.label;
          }
  std::cout << "[measured] " << sweep.runs << " heavy sliders on light rows, " << name_of(integrator) << ": "
            << sweep.off << " off, worst " << sweep.worst << " of Eq. 4 (" << sweep.worst_label << ")\n";
  return sweep;
}

// A slider whose base reaction acts at half its half-length ahead of its centre, from rest:
// the substep solver holds every run of the class to Eq. 4, the row in place, at mass ratios
// up to 290 (measured 2026-12-05, revision 2026-12-05.7: worst 2.0e-3 of Eq. 4).
TEST(HeavySliders, AHeavySliderFromRestCrossesRowsOfMuchLighterBlocksSubstep) {
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double row_share : {0.1, 0.3, 1.0}) {
        const LightRowRun run = run_light_row({slope, 0.5, row_share, 0.0, mirrored}, Integrator::Substep);
        ASSERT_EQ(run.result.summary.status, RunStatus::Completed) << run.label << ": " << run.result.summary.message;
        EXPECT_LT(run.error, kDisplacementTolerance) << run.label << ": worst at t = " << run.when << " s";
        EXPECT_LT(run.row_moved, kRowMovement) << run.label;
        EXPECT_LT(run.result.summary.solver.worst_penetration_ratio, kMaxPenetrationRatio) << run.label;
      }
}

// The same squat sliders at the Vajont scenes' time.step of 10 ms (x 4 substeps). Until model
// revision 2026-12-05.9 14 of the 18 were 1.4-8.8 % off (the known defect below held them
// too): the lighter row blocks stayed up to the 0.4 % of their size at which the position
// correction started deep in the plane, and the slider rode tilted on them; a tilt of delta lowers the friction along the slope by delta (1 + tan^2 phi),
// which a slope 1 deg steeper than phi magnifies 17-24 times. Small scenes now correct from
// 2.5e-4 (control.deep_overlap_ratio's automatic value, forward/options.hpp).
TEST(HeavySliders, SquatSlidersFromRestCrossFreeRowsAtTenMillisecondsSubstep) {
  const LightRowSweep sweep = sweep_light_rows(Integrator::Substep, {0.5}, {0.0}, 0.01);
  EXPECT_EQ(sweep.off, 0) << "worst " << sweep.worst << " of Eq. 4 (" << sweep.worst_label << ")";
}

// control.deep_overlap_ratio is the depth the lighter blocks rest at: the 30 deg slider on the
// 9 cm blocks (a mass ratio of 20) at 10 ms, asked for the landslide meshes' 4e-3, ends with a
// point overlapping more than 2e-3 of its smaller block and is more than 1 % off Eq. 4
// (measured 8.8 %); automatic (2.5e-4 in a scene this small), under 1e-3 and within 1 %.
TEST(HeavySliders, TheDeepOverlapRatioSetsHowDeepTheLighterBlocksRest) {
  LightRow c;
  c.slope = 30.0, c.r = 0.5, c.row_share = 0.3, c.step = 0.01;
  c.deep_overlap_ratio = kDeepOverlapLargeScene;
  const LightRowRun coarse = run_light_row(c, Integrator::Substep);
  ASSERT_EQ(coarse.result.summary.status, RunStatus::Completed) << coarse.result.summary.message;
  EXPECT_DOUBLE_EQ(coarse.result.summary.solver.deep_overlap_ratio, kDeepOverlapLargeScene);
  EXPECT_GT(coarse.result.summary.solver.worst_penetration_ratio, 2e-3);
  EXPECT_GT(coarse.error, kDisplacementTolerance);
  c.deep_overlap_ratio = 0.0;
  const LightRowRun automatic = run_light_row(c, Integrator::Substep);
  ASSERT_EQ(automatic.result.summary.status, RunStatus::Completed) << automatic.result.summary.message;
  EXPECT_DOUBLE_EQ(automatic.result.summary.solver.deep_overlap_ratio, kDeepOverlapSmallScene);
  EXPECT_LT(automatic.result.summary.solver.worst_penetration_ratio, 1e-3);
  EXPECT_LT(automatic.error, kDisplacementTolerance);
}

// KNOWN DEFECT (found 2026-12-05, revision 2026-12-05.7; docs/theory.md, Known limits (j)):
// tall sliders (r 0.8-0.95) from rest, 13 of 54 runs off (8 on the 3 cm blocks, 5 on the 9 cm
// ones), worst 50 %; at 3 m/s every r from 0.5 up, 19 of 72 off, all on the 3 cm blocks, worst
// 67 % (revision 2026-12-05.9; at .05.7, 22 of 54, worst 99.5 %, stopped at the first joint
// rocking on its front corner, and 20 of 72).
TEST(HeavySliders, DISABLED_TallOrFastHeavySlidersCrossRowsOfMuchLighterBlocksSubstep) {
  const LightRowSweep still = sweep_light_rows(Integrator::Substep, {0.8, 0.9, 0.95}, {0.0});
  const LightRowSweep fast = sweep_light_rows(Integrator::Substep, {0.5, 0.8, 0.9, 0.95}, {3.0});
  EXPECT_EQ(still.off + fast.off, 0);
}

// KNOWN DEFECT (found 2026-12-05, revision 2026-12-05.8; docs/theory.md, Known limits (j)):
// tall sliders (r 0.8-0.95) at the Vajont scenes' time.step of 10 ms (x 4 substeps, the
// default), from rest: 50 of 54 runs off at revision 2026-12-05.9, 1.0-74 %, the 0.3 m row
// blocks too (14 of 18), which the slider outweighs only 3-6 times (at .05.8 every one of the
// 54, and 14 of the 18 squat ones that SquatSlidersFromRestCrossFreeRowsAtTenMilliseconds-
// Substep now holds; at Vajont's x 3, 70 of 72). The same sliders on fixed joints at 10 ms keep
// within 0.3 % (216 runs of test_tall_sliders.cpp's class). A lighter block under a tall
// slider's front corner carries nearly all its weight: the cold first substeps of the quiet
// start and Gauss-Seidel under a heavier block leave it deep in the plane, the slider tilts
// onto it, and the next block's edge stands proud of the slider's corner (theory.md (j)).
TEST(HeavySliders, DISABLED_TallSlidersFromRestCrossFreeRowsAtTenMillisecondsSubstep) {
  const LightRowSweep sweep = sweep_light_rows(Integrator::Substep, {0.8, 0.9, 0.95}, {0.0}, 0.01);
  EXPECT_EQ(sweep.off, 0);
}

// KNOWN DEFECT (found 2026-12-05, revision 2026-12-05.7; docs/theory.md, Known limits (j)):
// the implicit solver from rest: 37 of 72 runs off: all 24 on the 3 cm blocks (3.1-32 %, at
// r = 0.5 too), 11 of 24 on the 9 cm blocks (up to 22 %), 2 of 24 on the 0.3 m blocks (1.3 %,
// a start 2.5 ms late: the elastic start of Known limits (i)). A run on the 3 cm blocks takes
// 20-440 s (the substep solver's under a second). Since revision 2026-12-05.8 `auto` runs
// scenes with a block on one 30 or more times lighter on the substep solver.
TEST(HeavySliders, DISABLED_HeavySlidersFromRestCrossRowsOfMuchLighterBlocksImplicit) {
  const LightRowSweep sweep = sweep_light_rows(Integrator::Implicit, {0.5, 0.8, 0.9, 0.95}, {0.0});
  EXPECT_EQ(sweep.off, 0);
}

// The class is found at t = 0 (forward/common/known_limits.hpp): the slider resting on a row block
// at the mass ratio of its construction, to rounding (1e-9), both ways down, heavy on light from
// 30 times up (every run on the 3 cm blocks, 120-550 times; on the 9 cm blocks those of 30
// times and more) and not below (the 0.3 m blocks, 1-6 times).
TEST(HeavySliders, TheHeavyOnLightClassIsFoundAtTheStart) {
  int heavy = 0, not_heavy = 0;
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : {0.5, 0.95})
        for (const double row_share : {0.1, 0.3, 1.0}) {
          const LightRow c{slope, r, row_share, 0.0, mirrored};
          int row_blocks = 0;
          Scene scene = light_row_scene(c, Integrator::Auto, row_blocks);
          if (mirrored) scene = mirrored_scene(scene);
          const BlockSystem s = build_block_system(scene);
          const HeavyOnLight found = find_known_limits(scene, s).heavy;
          const double ratio = light_row_mass_ratio(c);
          ASSERT_GE(found.heavy, 0) << slope << " deg, r " << r << ", row share " << row_share;
          EXPECT_EQ(s.block_names[found.heavy], "slider");
          EXPECT_EQ(s.block_names[found.light].rfind("row_", 0), 0u) << s.block_names[found.light];
          EXPECT_NEAR(found.ratio, ratio, 1e-9 * ratio) << slope << " deg, r " << r << ", row share " << row_share;
          EXPECT_EQ(is_heavy_on_light(found), ratio >= kHeavyOnLightRatio) << ratio;
          (is_heavy_on_light(found) ? heavy : not_heavy)++;
        }
  EXPECT_EQ(heavy, 18);  // twelve on 3 cm blocks, six on 9 cm ones (20 deg, and 30 deg at r = 0.95)
  EXPECT_EQ(not_heavy, 18);
  // Side by side on a level plane, a 1 m cube beside a 3 cm one (1100 times lighter): neither
  // rests on the other.
  Scene side = base_scene(kDuration1, kStep, kOutput, Integrator::Auto);
  add_interface(side, "floor", 30.0);
  side.default_interface = 0;
  const Slope level(0.0);
  add_plane_and_free_row(side, level, 2.0, 0.03, 0.03, 1);
  side.blocks.push_back(block("cube", box(level.at(0.03, 0.0), level.along, level.up, 1.0, 1.0), false, 0, "row"));
  EXPECT_LT(find_known_limits(side, build_block_system(side)).heavy.heavy, 0);
}

// time.integrator: auto runs a scene of the class on the substep solver from a mass ratio of 30
// (the implicit solver there: 29 of 38 runs from rest off; the substep solver 18 of 38, none at r = 0.5)
// and says why. Below it the implicit solver runs (from model revision 2026-12-06.8 to .13 the
// substep solver did, for the weaker joint between slider and row, Known limits (l), mended at .14;
// below 20 times the implicit solver ran 3 of 26 of (j)'s class off at .05.8, the substep solver
// none). The implicit solver, when asked, warns of the heavy pair; the substep solver does not.
// Both ways down, 1 ms of each (the choice is made at t = 0).
TEST(HeavySliders, AutoRunsHeavyBlocksOnMuchLighterOnesOnTheSubstepSolver) {
  for (const bool mirrored : {false, true})
    for (const double row_share : {0.1, 1.0}) {
      const LightRow c{30.0, 0.5, row_share, 0.0, mirrored};
      const bool heavy = light_row_mass_ratio(c) >= kHeavyOnLightRatio;  // 3 cm blocks: 180 times; 0.3 m: 1.8
      const auto run = [&](Integrator integrator) {
        int row_blocks = 0;
        Scene scene = light_row_scene(c, integrator, row_blocks);
        scene.duration = 0.001;
        if (mirrored) scene = mirrored_scene(scene);
        const SimulationResult r = simulate(scene);
        EXPECT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
        return r.summary;
      };
      const SimulationSummary automatic = run(Integrator::Auto);
      EXPECT_EQ(automatic.solver.integrator, heavy ? Integrator::Substep : Integrator::Implicit)
          << automatic.solver.reason;
      EXPECT_EQ(automatic.solver.reason.find("known limits (j)") != std::string::npos, heavy)
          << automatic.solver.reason;
      const SimulationSummary implicit = run(Integrator::Implicit);
      ASSERT_EQ(implicit.warnings.size(), heavy ? 1u : 0u);
      if (heavy) {
        EXPECT_NE(implicit.warnings[0].find("block 'slider' rests on block 'row_"), std::string::npos)
            << implicit.warnings[0];
        EXPECT_NE(implicit.warnings[0].find("known limits (j)"), std::string::npos) << implicit.warnings[0];
      }
      EXPECT_TRUE(run(Integrator::Substep).warnings.empty());
    }
}

}  // namespace
}  // namespace ddafit
