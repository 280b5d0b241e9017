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
};

struct LightRowRun {
  SimulationResult result;
  double error = 0.0, when = 0.0;  // against seed Eq. 4
  double row_moved = 0.0;          // m
  int row_blocks = 0;
  std::string label;
};

// The scene of the class above, run; the row blocks are blocks 1..n (block 0 the plane).
LightRowRun run_light_row(const LightRow& c, Integrator integrator) {
  const double friction = c.slope - 1.0;
  const double height = c.r * kSliderLength / std::tan(friction * kDegree);
  const double row_length = c.row_share * kSliderLength, row_height = 0.5 * row_length;
  const double a = eq4_acceleration(c.slope, friction);
  const double travel = 1.3 * (c.speed * kDuration1 + 0.5 * a * kDuration1 * kDuration1) + 0.1 * kSliderLength;
  int k = 1;  // the slider's front 2 % of a row block before a joint
  while (k * row_length - 0.02 * row_length - kSliderLength < 0.2 * kSliderLength) ++k;
  const double rear = k * row_length - 0.02 * row_length - kSliderLength;
  LightRowRun run;
  run.row_blocks = static_cast<int>(std::ceil((rear + 1.5 * kSliderLength + travel) / row_length));
  Scene s = base_scene(kDuration1, kStep, kOutput, integrator);
  const int holds = add_interface(s, "holds", 75.0);
  const int slides = add_interface(s, "slides", friction);
  s.contact_rules = {{"plane", "row", holds}, {"row", "row", holds}, {"slider", "row", slides}};
  s.default_interface = slides;
  const Slope slope(c.slope);
  add_plane_and_free_row(s, slope, run.row_blocks * row_length + 0.1, row_length, row_height, run.row_blocks);
  BlockInput slider = block("slider", box(slope.at(rear, row_height), slope.along, slope.up, kSliderLength, height),
                            false, 0, "slider");
  slider.velocity = c.speed * slope.along;
  s.blocks.push_back(slider);
  s.measure.push_back({"centre", slope.at(rear + 0.5 * kSliderLength, row_height + 0.5 * height)});
  run.result = run_watching_row(s, run.row_blocks, c.mirrored, run.row_moved);
  Crossing eq4;
  eq4.slope = c.slope, eq4.friction = friction, eq4.speed = c.speed;
  run.error = run.result.summary.status == RunStatus::Completed ? displacement_error(run.result, eq4, &run.when) : 1.0;
  run.label = name_of(integrator) + ": slope " + std::to_string(c.slope) + " deg, r " + std::to_string(c.r) +
              ", row blocks " + std::to_string(row_length) + " m (" + std::to_string(run.row_blocks) + "), v0 " +
              std::to_string(c.speed) + " m/s" + (c.mirrored ? ", mirrored" : "");
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

LightRowSweep sweep_light_rows(Integrator integrator, const std::vector<double>& ratios, const std::vector<double>& speeds) {
  LightRowSweep sweep;
  for (const bool mirrored : {false, true})
    for (const double slope : {20.0, 30.0, 40.0})
      for (const double r : ratios)
        for (const double row_share : {0.1, 0.3, 1.0})
          for (const double speed : speeds) {
            const LightRowRun run = run_light_row({slope, r, row_share, speed, mirrored}, integrator);
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

// KNOWN DEFECT (found 2026-12-05, revision 2026-12-05.7; docs/theory.md, Known limits (j)):
// tall sliders (r 0.8-0.95) from rest, 22 of 54 runs off, worst 99.5 % (stopped at the first
// joint, rocking on its front corner); at 3 m/s every r from 0.5 up, 20 of 72 off, worst 67 %.
// All but six of the 42 are on the rows of 3 cm blocks.
TEST(HeavySliders, DISABLED_TallOrFastHeavySlidersCrossRowsOfMuchLighterBlocksSubstep) {
  const LightRowSweep still = sweep_light_rows(Integrator::Substep, {0.8, 0.9, 0.95}, {0.0});
  const LightRowSweep fast = sweep_light_rows(Integrator::Substep, {0.5, 0.8, 0.9, 0.95}, {3.0});
  EXPECT_EQ(still.off + fast.off, 0);
}

// KNOWN DEFECT (found 2026-12-05, revision 2026-12-05.7; docs/theory.md, Known limits (j)):
// the implicit solver, which `time.integrator: auto` picks for scenes of under 100 free blocks,
// is off on this class from rest too, at r = 0.5 as well (see the note there for the counts);
// a run on the 3 cm blocks takes 15-190 s.
TEST(HeavySliders, DISABLED_HeavySlidersFromRestCrossRowsOfMuchLighterBlocksImplicit) {
  const LightRowSweep sweep = sweep_light_rows(Integrator::Implicit, {0.5, 0.8, 0.9, 0.95}, {0.0});
  EXPECT_EQ(sweep.off, 0);
}

}  // namespace
}  // namespace ddafit
