// A column of blocks at rest, the simplest deep mass: it must stay at rest. Found on
// Vajont section VII, whose resting mass (about 30 blocks deep) rattled at 0.4 m/s with
// 10 ms steps of three substeps; a column of ten blocks shows the same (docs/theory.md
// §13, "Split impulses"). Swept over block sizes 1-32 m and steps of 5-20 ms, because the
// soft step's failures fall at no simple boundary (1 m blocks fail at 5 ms x 4, 8 m ones at
// 10 ms x 3 but not at 20 ms x 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

// A w x h box with its lower-left corner at `corner` (verify/cases.hpp's block).
BlockInput box_block(const std::string& name, Vec2 corner, double width, double height, bool fixed) {
  return verification::block(name,
                             {corner, corner + Vec2(width, 0), corner + Vec2(width, height), corner + Vec2(0, height)},
                             fixed);
}

struct StepSetting {
  double step;   // s
  int substeps;
};

// `courses` courses of `per_course` blocks of w x w/2 on a fixed floor; the odd courses of a
// wall are laid in running bond and closed by half blocks, so that nothing overhangs. Rock
// of 2700 kg/m^3, joints of 35 deg. Measure points at the top course and every quarter.
Scene column_scene(int courses, int per_course, double w, StepSetting setting, bool split) {
  Scene s = verification::rock_scene(2700.0, 35.0, 5.0, setting.step, 0.05);
  s.options.integrator = Integrator::Substep;
  s.options.substeps = setting.substeps;
  s.options.split_impulses = split;
  const double h = 0.5 * w;
  s.blocks.push_back(box_block("floor", {-2 * w, -w}, (per_course + 4) * w, w, true));
  for (int c = 0; c < courses; ++c) {
    const bool odd = per_course > 1 && c % 2 == 1;
    double x = 0.0;
    for (int k = 0; k < per_course + (odd ? 1 : 0); ++k) {
      const double length = odd && (k == 0 || k == per_course) ? 0.5 * w : w;
      // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "b" + std::to_string(c).
      std::string name = "b";
      name += std::to_string(c) + "_" + std::to_string(k);
      s.blocks.push_back(box_block(name, {x, c * h}, length, h, false));
      x += length;
    }
  }
  for (int c = courses - 1; c >= 0; c -= std::max(1, courses / 4))
    s.measure.push_back({"course_" + std::to_string(c), {0.5 * per_course * w + 0.25 * w, (c + 0.5) * h}});
  return s;
}

struct Rest {
  bool completed = false;
  std::string message;
  double last_second_speed = 0.0;  // m/s, the fastest measure point over the last 1 s
  double movement = 0.0;           // m, the largest displacement of a measure point
};

Rest run_column(int courses, int per_course, double w, StepSetting setting, bool split,
                Integrator integrator = Integrator::Substep, bool top_down = false, bool floor_last = false) {
  Scene scene = column_scene(courses, per_course, w, setting, split);
  scene.options.integrator = integrator;
  // The same column with its blocks listed from the top course down (the floor first): the
  // contacts are then stored and swept in the other order.
  if (top_down) std::reverse(scene.blocks.begin() + 1, scene.blocks.end());
  // The floor listed after the column (as Vajont's bedrock region follows the slide): each
  // contact with the floor then has the column's block as its first block.
  if (floor_last) std::rotate(scene.blocks.begin(), scene.blocks.begin() + 1, scene.blocks.end());
  const SimulationResult r = simulate(scene);
  Rest out;
  out.completed = r.summary.status == RunStatus::Completed;
  out.message = r.summary.message;
  for (const HistoryRow& row : r.history) {
    if (row.time >= scene.duration - 1.0) out.last_second_speed = std::max(out.last_second_speed, row.velocity.norm());
    out.movement = std::max(out.movement, row.displacement.norm());
  }
  return out;
}

// The settings a user of 1-32 m blocks would pick (5 ms x 4 is the Vajont scene's) and the
// two coarser ones that make section VII twice as fast.
const StepSetting kResting[] = {{0.005, 4}, {0.01, 4}, {0.01, 3}};
const double kSizes[] = {1.0, 2.0, 4.0, 8.0, 16.0, 32.0};

// With split impulses every column stays at rest: its fastest point over the last second is
// under 0.01 m/s (a tenth of the default rest_speed; measured at most 0.0015 m/s) and no
// point moves more than 5 mm (the contacts' settling, measured at most 3.0 mm; a slide moves
// metres). The soft step fails 8 of these 18 (it creates energy and stops).
// The 18 ten-block columns with split impulses, each held to the bounds above.
void expect_split_impulses_hold_the_columns(bool top_down, bool floor_last = false) {
  for (double w : kSizes)
    for (StepSetting st : kResting) {
      const Rest r = run_column(10, 1, w, st, true, Integrator::Substep, top_down, floor_last);
      const std::string where = std::to_string(w) + " m blocks, " + std::to_string(st.step) + " s x " +
                                std::to_string(st.substeps) + (top_down ? ", listed top down" : "") +
                                (floor_last ? ", floor listed last: " : ": ") + r.message;
      EXPECT_TRUE(r.completed) << where;  // every column is run and reported, not only the first to fail
      if (!r.completed) continue;
      EXPECT_LT(r.last_second_speed, 0.01) << where;
      EXPECT_LT(r.movement, 0.005) << where;
    }
}

TEST(RestingColumn, SplitImpulsesHoldATenBlockColumnAtRest) { expect_split_impulses_hold_the_columns(false); }

// The same 18 columns listed from the top course down. Until model revision 2026-12-02.3 one
// failed: 16 m blocks at 10 ms x 3 still moved at 0.0154 m/s over the last second (bound 0.01;
// moved 1.2 mm), because the sweeps met a column's joints in the order of its blocks. They now
// meet them from the lowest up (prepare_contacts.hpp, colour_manifolds), whichever way the
// blocks are listed.
TEST(RestingColumn, SplitImpulsesHoldATenBlockColumnListedTopDown) { expect_split_impulses_hold_the_columns(true); }

// KNOWN DEFECT (found 2026-12-02, revision .12.02.4): the same 36 columns (floor up and top
// down) with the floor listed after the blocks. 3 of 36 stop with "contacts are creating
// energy", all of 1 m blocks: floor up at 10 ms x 3 (2.72 s), top down at 10 ms x 4 (3.74 s)
// and 10 ms x 3 (0.44 s). Traced on the second: after 3.7 s of a slow rocking (under 1.3 mm/s,
// as with the floor first), one joint of the column stops carrying within one substep's second
// relax sweep (the block above it takes -0.011 m/s), the blocks above fall for a few substeps
// at up to 0.036 m/s and the energy audit stops the run. The joints' heights differ, so the
// sweeps' colours are those of the floor-first column; what changes is which block of each
// contact is its first (the normal's sense, the narrow phase's reference face) and the order
// the impact groups and corrections list them in (sorting those lists by height: no change).
// Underneath: columns of 1 m blocks climb with the floor listed first too. The quiet start
// leaves every other joint overlapping by up to 0.24 mm (16 slops), the push-out sweep then takes
// it out slowly and lifts the column (the top block 0.62 mm up in 5 s at 10 ms x 4), so gravity's
// work since t = 0 turns negative and a small burst of motion trips the energy audit
// (docs/theory.md §13, "Limits of the substep solver").
// The other 33 hold within the bounds above.
// Cause found 2026-12-03 (docs/theory.md §13, "A flipped face drops its load"): the joint that
// "stops carrying" had flipped its reference face between two steps, and its points came back
// with new keys and no impulse. Found again by place, all 36 hold; that is not kept for
// unbonded points, because the impact sweeps' margins rely on the blow being dropped the same way.
TEST(RestingColumn, DISABLED_SplitImpulsesHoldATenBlockColumnWithTheFloorListedLast) {
  expect_split_impulses_hold_the_columns(false, true);
  expect_split_impulses_hold_the_columns(true, true);
}

// A wall 40 courses high and 12 blocks wide of 8 m blocks at 10 ms x 3, Vajont section VII's
// blocks and depth: at rest with split impulses (measured 0.0022 m/s, 1.5 mm); the soft step
// stops at 1.1 s with "contacts are creating energy".
TEST(RestingColumn, SplitImpulsesHoldATallWallAtRest) {
  const Rest r = run_column(40, 12, 8.0, {0.01, 3}, true);
  ASSERT_TRUE(r.completed) << r.message;
  EXPECT_LT(r.last_second_speed, 0.01);
  EXPECT_LT(r.movement, 0.005);
}

// Where a scheme cannot hold a column (the soft step at most of these settings; split
// impulses at 5 ms substeps, 20 ms x 4, with blocks under 16 m), the run stops with the energy
// audit's diagnosis, which names the substeps to raise, and never returns a moving column as
// a result: a completed run is at rest (16-32 m blocks at 20 ms x 4 with split impulses complete
// still settling at 0.045 m/s, under rest_speed, and are held to 0.1 m/s here).
TEST(RestingColumn, EitherSchemeHoldsTheColumnOrStopsWithADiagnosis) {
  for (bool split : {false, true})
    for (double w : kSizes)
      for (StepSetting st : {StepSetting{0.005, 4}, StepSetting{0.01, 4}, StepSetting{0.01, 3}, StepSetting{0.02, 4}}) {
        const Rest r = run_column(10, 1, w, st, split);
        const std::string where = std::string(split ? "split" : "soft") + ", " + std::to_string(w) + " m blocks, " +
                                  std::to_string(st.step) + " s x " + std::to_string(st.substeps);
        if (r.completed) {
          EXPECT_LT(r.last_second_speed, 0.1) << where;
        } else {
          EXPECT_NE(r.message.find("creating energy"), std::string::npos) << where << ": " << r.message;
          EXPECT_NE(r.message.find("time.substeps"), std::string::npos) << where << ": " << r.message;
        }
      }
}

// The implicit solver, the reference, holds every column at every step of the sweep
// including 20 ms, listed from the floor up and from the top down, with the floor listed first
// or last: fastest point over the last second at most 6.4e-5 m/s (floor up) and 1.1e-4 m/s (top
// down; 1.2e-4 m/s with the floor last), movement at most 0.12 mm and 0.87 mm (the elastic
// shortening and contact compression of ten 32 m blocks; the order changes how the column
// settles into its contacts at the start, not whether it holds), held to 0.01 m/s and 1 mm.
TEST(RestingColumn, TheImplicitSolverHoldsEveryColumnAtRest) {
  for (const bool floor_last : {false, true})
    for (const bool top_down : {false, true})
      for (double w : kSizes)
        for (StepSetting st : {StepSetting{0.005, 4}, StepSetting{0.01, 4}, StepSetting{0.02, 4}}) {
          const Rest r = run_column(10, 1, w, st, false, Integrator::Implicit, top_down, floor_last);
          const std::string where = std::to_string(w) + " m blocks, " + std::to_string(st.step) + " s" +
                                    (top_down ? ", listed top down" : "") +
                                    (floor_last ? ", floor listed last: " : ": ") + r.message;
          ASSERT_TRUE(r.completed) << where;
          EXPECT_LT(r.last_second_speed, 0.01) << where;
          EXPECT_LT(r.movement, 0.001) << where;
          std::cout << "[measured] implicit, " << where << " last-second speed " << r.last_second_speed
                    << " m/s, movement " << r.movement << " m\n";
        }
}

}  // namespace
}  // namespace ddafit
