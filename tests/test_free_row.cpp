// A slider across the joints of a row of free blocks resting on a fixed plane: the row's
// joints are flush only as far as its blocks sit still, and a heavy slider presses the blocks
// under it deeper into the plane than the unloaded one ahead, whose edge then stands proud
// (forward/contact/manifold.hpp, "Proud edges"). Both solvers, slopes 15-35 deg, rows of
// 0.15-1.0 m blocks, light and heavy sliders, from rest (and, at coarse steps, arriving at
// 10-30 m/s; on rows of cubes, arriving at 1-6 m/s); the tolerances of
// test_joint_crossing.cpp (1 % of seed Eq. 4 where the slider has moved 1 cm; overlaps under
// 1 % of the smaller block), and the row in place within 1 mm.
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <tuple>
#include <string>
#include <vector>

#include "forward/mirror.hpp"
#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

class FreeRowSolver : public ::testing::TestWithParam<Integrator> {};

constexpr double kRowMovement = 1e-3;  // m: the row's elastic settling is micrometres

// A slider on a row of free blocks (row_height thick) that rest on a fixed plane: the row held
// to the plane (and block to block) at `hold`, the slider on the row at `slide` (degrees).
// Returns the run and how far any block of the row moved.
struct FreeRow {
  double slope = 28.0, hold = 45.0, slide = 18.0;
  double row_length = 0.4, row_height = 0.3, plane_length = 14.0;
  int row_blocks = 30;
  bool mirrored = false;  // run as its mirror image, descending to the left (forward/mirror.hpp)
  double length = 1.2, height = 0.6, rear = 0.0;  // the slider, its rear along the slope
  double speed = 0.0;                             // the slider's, down the slope at t = 0 (m/s)
  double step = kStep;                            // time.step (s)
  int substeps = SimulationOptions{}.substeps;     // time.substeps (the substep solver)
  double max_displacement_ratio = SimulationOptions{}.max_displacement_ratio;
};
struct FreeRowRun {
  SimulationResult result;
  double row_moved = 0.0;  // m
};
FreeRowRun run_free_row(const FreeRow& f, Integrator integrator) {
  Scene s = base_scene(kDuration, f.step, kOutput, integrator);
  s.options.max_displacement_ratio = f.max_displacement_ratio;
  s.options.substeps = f.substeps;
  const int holds = add_interface(s, "holds", f.hold);
  const int slides = add_interface(s, "slides", f.slide);
  s.contact_rules = {{"plane", "row", holds}, {"row", "row", holds}, {"slider", "row", slides}};
  s.default_interface = slides;
  const Slope slope(f.slope);
  const double row_height = f.row_height;
  add_plane_and_free_row(s, slope, f.plane_length, f.row_length, row_height, f.row_blocks);
  BlockInput slider = block("slider", box(slope.at(f.rear, row_height), slope.along, slope.up, f.length, f.height),
                            false, 0, "slider");
  slider.velocity = f.speed * slope.along;
  s.blocks.push_back(slider);
  s.measure.push_back({"centre", slope.at(f.rear + 0.5 * f.length, row_height + 0.5 * f.height)});
  FreeRowRun run;
  run.result = run_watching_row(s, f.row_blocks, f.mirrored, run.row_moved);
  return run;
}

// The run of a free row against seed Eq. 4 (slope and slide friction) and the row in place.
void expect_row_crossed(const FreeRowRun& run, const FreeRow& f, const std::string& label) {
  const SimulationResult& r = run.result;
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  EXPECT_LT(run.row_moved, kRowMovement) << label;
  Crossing c;
  c.slope = f.slope;
  c.friction = f.slide;
  c.speed = f.speed;
  double when = 0.0;
  const double error = displacement_error(r, c, &when);
  EXPECT_LT(error, kDisplacementTolerance) << label << ": worst at t = " << when << " s";
  EXPECT_LT(r.summary.solver.worst_penetration_ratio, kMaxPenetrationRatio) << label;
  std::cout << "[measured] " << label << ": row moved " << run.row_moved << " m, slider displacement error " << error
            << "\n";
}

// The slider on a row of free blocks that rest on a fixed plane: the row's joints are
// flush only as far as the row's blocks sit still, and they must (friction 45 deg on a
// 28 deg slope, the slider's drag included: the row needs tan(phi) of 0.53 + 0.33 x 0.27,
// and has 1.0). The row stays put within 1 mm (its elastic settling is micrometres), and
// the slider follows seed Eq. 4.
TEST_P(FreeRowSolver, SliderAcrossARowOfFreeBlocksLeavesTheRowInPlace) {
  for (const double row_length : {0.4, 1.0}) {
    FreeRow f;
    f.row_length = row_length;
    f.row_blocks = static_cast<int>(12.0 / row_length);
    f.rear = 2.0 * row_length - 0.02 - f.length;
    expect_row_crossed(run_free_row(f, GetParam()), f,
                       name_of(GetParam()) + ", row of " + std::to_string(row_length) + " m blocks");
  }
}

// A heavy slider starting from rest on a gentle slope over a row of free blocks: a 3 m x 1.5 m
// slider at 15 deg, friction 8 deg (seed Eq. 4: 1.2 m/s^2), over rows of 0.15-1.0 m blocks
// 0.3 m thick held to the plane at 60 deg. It must follow Eq. 4 and leave the row in place (1 mm).
// The loaded blocks under it sit 1.6 um deeper in their soft contact with the plane than the
// unloaded one ahead, whose edge stands proud by that much. Until revision 2026-12-01.1 the
// substep solver stopped the slider dead where its front corner first crossed a joint (2.2 cm
// in, against Eq. 4's 1.36 m in 1.5 s): the joint face, overlapped less than the proud edge,
// was the separating axis (forward/contact/manifold.hpp, "Proud edges"; test_flush_neighbours.cpp).
// The implicit solver's 0.15 m row is left out: 99 s.
void expect_heavy_slider_crosses_free_row(Integrator integrator, const std::vector<double>& row_lengths,
                                          double slope = 15.0, double slide = 8.0,
                                          double max_displacement_ratio = SimulationOptions{}.max_displacement_ratio,
                                          double plane_length = 12.0, int row_blocks = 0) {
  for (const double row_length : row_lengths) {
    FreeRow f;
    f.slope = slope, f.hold = 60.0, f.slide = slide;
    f.max_displacement_ratio = max_displacement_ratio;
    f.row_length = row_length, f.plane_length = plane_length;
    f.row_blocks = row_blocks > 0 ? row_blocks : static_cast<int>(std::ceil((plane_length - 1.0) / row_length));
    f.length = 3.0, f.height = 1.5;
    int k = 1;
    while (k * row_length - 0.02 - f.length < 0.1) ++k;
    f.rear = k * row_length - 0.02 - f.length;  // the front 2 cm before a joint
    expect_row_crossed(run_free_row(f, integrator), f,
                       name_of(integrator) + ", 3 m slider from rest at " + std::to_string(slope) + " deg, row of " +
                           std::to_string(row_length) + " m blocks, plane " + std::to_string(plane_length) + " m");
  }
}

TEST(JointCrossingFreeRow, AHeavySliderFromRestCrossesARowOfFreeBlocksSubstep) {
  expect_heavy_slider_crosses_free_row(Integrator::Substep, {0.15, 0.4, 1.0});
}

TEST(JointCrossingFreeRow, AHeavySliderFromRestCrossesARowOfFreeBlocksImplicit) {
  expect_heavy_slider_crosses_free_row(Integrator::Implicit, {0.4, 1.0});
}

// The same slider from rest on steeper slopes (seed Eq. 4: 1.8 and 4.9 m/s^2), both solvers:
// the proud edge is there at any slope; only the time the corner spends near it changes.
// The implicit solver at 28 deg passes too (8.7e-4 and 1.2e-4 of Eq. 4 on rows of 0.4 and
// 1.0 m) but takes 50 s, its row creeping under the slider (0.19 mm); it is left out.
TEST_P(FreeRowSolver, AHeavySliderFromRestCrossesAFreeRowOnSteeperSlopes) {
  for (const auto& [slope, slide] : {std::pair{28.0, 18.0}, std::pair{35.0, 5.0}})
    if (GetParam() == Integrator::Substep || slope > 30.0)
      expect_heavy_slider_crosses_free_row(GetParam(), {0.4, 1.0}, slope, slide);
}

// The same slider at 15 deg with the displacement limit at 2e-4 of half the model (field notes:
// 1e-3 to 1e-2; Vajont runs 2e-4 of 1250 m). The linear slop (1e-3 of the largest move) is then
// about 1.3 um, under the 1.6 um the edge ahead stands proud: at revision 2026-12-01.1 the
// substep solver hooked again on the row of 1.0 m blocks (17.8 % short of seed Eq. 4). Since .2
// the proud edge's depth has a floor of 5e-6 of the smaller block (collide.hpp, kProudRatio).
// The implicit solver crossed the 12 m plane's row (2e-5), but on a 13.36 m plane under 12 row
// blocks (the exploratory scene of docs/verification.md; the limit, relative to the model, then
// allows larger moves) it fell 38 % short at .1 and still 19 % at .2: points frozen locked past
// their Coulomb cap, mended by revision 2026-12-02.1 (docs/theory.md §5, "Capped locks"; 7e-5
// since). Both scenes, both solvers.
TEST_P(FreeRowSolver, AHeavySliderCrossesAFreeRowUnderASmallDisplacementLimit) {
  expect_heavy_slider_crosses_free_row(GetParam(), {1.0}, 15.0, 8.0, 2e-4);
  expect_heavy_slider_crosses_free_row(GetParam(), {1.0}, 15.0, 8.0, 2e-4, 13.36, 12);
}

// Lays out a sweep's run: a plane long enough for the slider's 1.5 s at `f.speed`, the row along
// all of it, and the slider's front `gap` before a joint of the row.
void lay_out_along_the_row(FreeRow& f, double gap) {
  f.plane_length = f.speed * kDuration + 10.0 + 2.0 * f.length;
  f.row_blocks = static_cast<int>(std::ceil((f.plane_length - 1.0) / f.row_length));
  int k = 1;
  while (k * f.row_length - gap - f.length < 0.1) ++k;
  f.rear = k * f.row_length - gap - f.length;
}

// What a sweep's run got wrong, after `label`: not completed, more than 1 % off seed Eq. 4, or
// the row moved more than kRowMovement. Empty when the run is within both.
std::string free_row_failure(const FreeRowRun& run, const FreeRow& f, const std::string& label) {
  if (run.result.summary.status != RunStatus::Completed) return label + ": " + run.result.summary.message;
  Crossing c;
  c.slope = f.slope, c.friction = f.slide, c.speed = f.speed;
  double when = 0.0;
  const double error = displacement_error(run.result, c, &when);
  if (error < kDisplacementTolerance && run.row_moved < kRowMovement) return {};
  return label + ": " + std::to_string(error) + " off Eq. 4, row moved " + std::to_string(run.row_moved) + " m";
}

// Sliders on a free row at the coarse steps of a landslide run (10 ms x 3, Vajont's, 10 ms x 4
// and 5 ms x 4; the tests above run 1 ms), substep solver: a 1.2 x 0.6 and a 3 x 1.5 m slider
// over rows of 0.4 and 1.0 m blocks, at 15 deg (friction 8, the row held at 60) and 28 deg (18,
// held at 45), from rest or arriving at `speed`; a plane long enough for 1.5 s. Returns the
// labels of the runs off seed Eq. 4 by more than 1 % or with the row moved more than 1 mm.
std::vector<std::string> free_rows_at_coarse_steps(std::initializer_list<double> speeds,
                                                   std::initializer_list<std::tuple<double, double, double>> slopes,
                                                   int* runs) {
  std::vector<std::string> off;
  for (const auto& [step, substeps] : {std::pair{0.01, 3}, {0.01, 4}, {0.005, 4}})
    for (const double speed : speeds)
      for (const auto& [slope, slide, hold] : slopes)
        for (const auto& [length, height] : {std::pair{1.2, 0.6}, std::pair{3.0, 1.5}})
          for (const double row_length : {0.4, 1.0}) {
            FreeRow f;
            f.slope = slope, f.slide = slide, f.hold = hold, f.speed = speed;
            f.step = step, f.substeps = substeps;
            f.length = length, f.height = height, f.row_length = row_length;
            lay_out_along_the_row(f, 0.02);  // the front 2 cm before a joint
            const FreeRowRun run = run_free_row(f, Integrator::Substep);
            char label[200];
            std::snprintf(label, sizeof label,
                          "%g m/s, %g deg (friction %g), slider %g x %g m, row of %g m, %g ms x %d", speed, slope,
                          slide, length, height, row_length, step * 1000, substeps);
            ++*runs;
            if (std::string failure = free_row_failure(run, f, label); !failure.empty()) off.push_back(failure);
          }
  return off;
}

// The implicit solver on the same class at 10 and 20 ms (the tests above run it at 1 ms): sliders
// of 1.2 x 0.6 and 3 x 1.5 m over rows of 0.4 and 1.0 m blocks, at 15 deg (friction 8, the row
// held at 60) and 28 deg (18, held at 45), from rest and arriving at 2 m/s. Measured (2026-12-05,
// revision .12.05.12): all 32 within 1 % of seed Eq. 4 with the row in place, as at 5 ms (16 more,
// probe); the 3 m slider arriving at 15 deg takes 1-12 s of wall, the rest under 1 s.
TEST(JointCrossingFreeRow, SlidersCrossAFreeRowAtCoarseStepsImplicit) {
  int runs = 0;
  std::vector<std::string> off;
  for (const double step : {0.01, 0.02})
    for (const double speed : {0.0, 2.0})
      for (const auto& [slope, slide, hold] : {std::tuple{15.0, 8.0, 60.0}, std::tuple{28.0, 18.0, 45.0}})
        for (const auto& [length, height] : {std::pair{1.2, 0.6}, std::pair{3.0, 1.5}})
          for (const double row_length : {0.4, 1.0}) {
            FreeRow f;
            f.slope = slope, f.slide = slide, f.hold = hold, f.speed = speed, f.step = step;
            f.length = length, f.height = height, f.row_length = row_length;
            lay_out_along_the_row(f, 0.02);  // the front 2 cm before a joint
            char label[200];
            std::snprintf(label, sizeof label, "%g m/s, %g deg (friction %g), slider %g x %g m, row of %g m, %g ms",
                          speed, slope, slide, length, height, row_length, step * 1000);
            ++runs;
            const FreeRowRun run = run_free_row(f, Integrator::Implicit);
            if (std::string failure = free_row_failure(run, f, label); !failure.empty()) off.push_back(failure);
          }
  EXPECT_EQ(runs, 32);
  std::string listed;
  for (const std::string& failure : off) listed += "\n  " + failure;
  EXPECT_TRUE(off.empty()) << off.size() << " of " << runs << " off seed Eq. 4 or with the row moved:" << listed;
  std::printf("[measured] %d sliders on free rows at 10 and 20 ms, implicit: %zu off\n", runs, off.size());
}

// From rest at 15 deg, the heavy slider's scene of AHeavySliderFromRestCrossesARowOfFreeBlocks at
// coarse steps (12 runs). Until model revision 2026-12-04.1 the 3 x 1.5 m slider on 0.4 m blocks
// hooked at the first joint at 10 ms x 4 and x 3 (0 % of Eq. 4's travel): a substep of 2.5-3.3 ms
// lets the loaded row blocks rest deeper than the unloaded one ahead by about |g| h^2 (61-109 um;
// traced at 10 ms x 4: the slider 76 um into the blocks under its front), more than the slop of
// this 16 m scene (40 um) that bounded "Proud edges", and the quiet start slides the slider into
// that edge before t = 0 (below). The bound now includes the substep's sag (collide.hpp,
// kSagRatio). Worst since: 2.1e-4 of Eq. 4.
TEST(JointCrossingFreeRow, AHeavySliderFromRestCrossesAFreeRowAtCoarseStepsSubstep) {
  int runs = 0;
  const std::vector<std::string> off = free_rows_at_coarse_steps({0.0}, {{15.0, 8.0, 60.0}}, &runs);
  EXPECT_EQ(runs, 12);
  for (const std::string& o : off) ADD_FAILURE() << o;
}

// The class above from rest and arriving at 10 and 30 m/s, and at 28 deg too (72 runs), each
// within 1 % of seed Eq. 4 with the row moved less than 1 mm. A known defect from 2026-12-04 to
// model revision 2026-12-05.1 ("Proud edges" reads the face the blocks were held up by within its
// whole window; the cube-row tests below), which mended it: 0 of 72 off since. Before it, 8 failed
// at revision 2026-12-04.1 (16 before that), 5 at .2 (the history below). The
// 3 x 1.5 m slider arriving at 10-30 m/s drags the row of 0.4 m blocks along (16-25 m, 61-83 % off Eq. 4) at
// 10 ms x 3 and x 4, and a row of 1.0 m blocks 4 m at 5 ms x 4 (30 m/s, 20 % off); from rest at
// 28 deg at 10 ms x 4 the row creeps 1.7 mm. At 1 ms every such run passes, and the implicit
// solver passes them at 10 ms. Traced (10 m/s, 15 deg, 10 ms x 4): the quiet start's 500 steps,
// each restarted from rest, let the slider (not in equilibrium: 1.2 m/s^2 down the slope) slide
// 1/2 a dt^2 a step, 3 cm in all at 10 ms (0.3 mm at 1 ms), so it starts at t = 0 with its front
// face already against the joint face of the row block 2 cm ahead (that manifold has the joint's
// normal and an impulse at t = 0) and rams it at 10 m/s. The quiet start is one cause, not the
// only one. At revision 2026-12-04.2 (a settling group leaves out its slipping joints; the cube-row
// test below) 5 fail: the 3 x 1.5 m slider on 0.4 m blocks at 10 ms (10 and 30 m/s, 15 and 28 deg;
// 68-82 % off, rows driven 18-26 m) and on 1.0 m blocks at 5 ms x 4 (30 m/s, 20 %, 4.0 m). Without
// any impact group (an environment switch, not kept) 5 fail as well. docs/theory.md §13, "Limits
// of the substep solver".
TEST(JointCrossingFreeRow, SlidersArrivingFastCrossAFreeRowAtCoarseStepsSubstep) {
  int runs = 0;
  const std::vector<std::string> off =
      free_rows_at_coarse_steps({0.0, 10.0, 30.0}, {{15.0, 8.0, 60.0}, {28.0, 18.0, 45.0}}, &runs);
  EXPECT_EQ(runs, 72);
  std::printf("[measured] %d sliders arriving fast on free rows at coarse steps, substep: %zu off\n", runs, off.size());
  for (const std::string& o : off) ADD_FAILURE() << o;
}

// The cube-row class at one step: the failures of its 72 runs, counted in `runs`. The sliders
// outweigh a cube 3.1, 28, 50 and 450 times (1 x 0.5 m on 0.4 m cubes, 3 x 1.5 m on 0.4 m,
// 1 x 0.5 m on 0.1 m, 3 x 1.5 m on 0.1 m).
std::vector<std::string> cube_rows_at(double step, int substeps, int* runs) {
  std::vector<std::string> off;
  for (const auto& [slope, slide] : {std::pair{25.0, 17.0}, {35.0, 27.0}, {35.0, 33.0}})
    for (const double speed : {1.0, 3.0, 6.0})
      for (const auto& [length, height] : {std::pair{1.0, 0.5}, std::pair{3.0, 1.5}})
        for (const double cube : {0.1, 0.4})
          for (const bool mirrored : {false, true}) {
            FreeRow f;
            f.slope = slope, f.slide = slide, f.hold = 60.0, f.speed = speed, f.mirrored = mirrored;
            f.length = length, f.height = height, f.row_length = cube, f.row_height = cube;
            f.step = step, f.substeps = substeps;
            lay_out_along_the_row(f, 0.02 * cube);  // the front 2 % of a cube before a joint
            const FreeRowRun run = run_free_row(f, Integrator::Substep);
            ++*runs;
            char label[240];
            std::snprintf(label, sizeof label,
                          "%g m/s, %g deg (friction %g), slider %g x %g m, cubes of %g m, %g ms x %d%s", speed,
                          slope, slide, length, height, cube, 1e3 * step, substeps,
                          mirrored ? ", descending to the left" : "");
            if (std::string failure = free_row_failure(run, f, label); !failure.empty()) off.push_back(failure);
          }
  return off;
}

// Substep solver at the default 1 ms x 4: sliders of 1 x 0.5 and 3 x 1.5 m arriving at 1, 3 and
// 6 m/s on rows of cubes (0.1 and 0.4 m, each stable on its own: the row held at 60 deg, the
// slider at 17-33 deg on 25-35 deg slopes), both ways down: 72 runs, each within 1 % of seed
// Eq. 4 with the row moved less than 1 mm. The sweeps above start from rest, or arrive fast only
// at coarse steps on rows 0.3 m thick. Found 2026-12-04 by a black-box sweep through `ddafit
// simulate`: until model revision 2026-12-04.2, 18 of the 72 failed, worst the 3 m slider at 6 m/s
// on 0.1 m cubes at 35 deg (friction 33), 48 % off with the row driven 19.6 m. The cause (traced
// 2026-12-04 with environment switches, not kept): a cube rattling under the heavy slider at a
// few mm/s was marked struck, its settling group took in the slider, and the direct solve put the
// slider's load on the one or two cubes standing micrometres proud (the slider pressed on one cube
// with 26 times its share of the slider's weight), whose friction then drove the row. Without
// impact groups, or without settling, none of the 72 failed; more sweeps in the group solve (16: 9 off), friction solved with the normals
// (staggered, 8 rounds: still off) and the soft step (1 off) did not cure it. Since .2 a settling
// group leaves out the joints that slip faster than three times the impact margin
// (converge_impacts.cpp, kSlipShare): 0 of 72 off.
TEST(JointCrossingFreeRow, SlidersArrivingOnARowOfCubesLeaveTheRowInPlaceSubstep) {
  int runs = 0;
  const std::vector<std::string> off = cube_rows_at(kStep, SimulationOptions{}.substeps, &runs);
  EXPECT_EQ(runs, 72);
  std::printf("[measured] %d sliders arriving on rows of cubes, substep: %zu off\n", runs, off.size());
  for (const std::string& o : off) ADD_FAILURE() << o;
}

// The cube-row class at 2 ms x 4 (72 runs): each within 1 % of seed Eq. 4, the row moved less
// than 1 mm. Two defects were mended in turn:
// - Until model revision 2026-12-05.1, 8 runs of the 1 x 0.5 m slider on 0.1 m cubes (50 times a
//   cube) failed, 8-70 % off. Traced (3 m/s, 35 deg, friction 33): the loaded cubes sink deeper
//   into the plane than the unloaded one ahead, whose edge then stood 49-51 um proud of the
//   slider's face (the slop is 29.5 um); the slider's corner, 9.9 um across the joint,
//   overlapped the cube's top by 51 um, past the separating axis's overlap plus the slop, so
//   "Proud edges" let the cube's rear face be the contact, and the slider was thrown off the row
//   at 1 m/s. Since .1 the rule takes the face the blocks were held up by wherever it overlaps no
//   deeper than its window (twice the slop: the corner rests up to the slop deep and the edge
//   stands up to the slop proud; tests/test_flush_neighbours.cpp).
// - Until model revision 2026-12-05.2, 12 of the 18 runs of the 3 x 1.5 m slider on 0.1 m cubes
//   (450 times a cube) failed, with the impact groups switched off as well (an environment switch,
//   not kept): Gauss-Seidel sweeps converge slowest at a large mass ratio, and two sweeps a
//   substep left the slider sinking into the cube it had just reached. Six sweeps for every
//   manifold mended them (a probe, not kept); since .2 the manifolds of a block beside one at
//   least 30 times heavier get 8 more sweeps a substep (forward/substep/converge_heavy.hpp): 0 off.
TEST(JointCrossingFreeRow, SlidersArrivingOnARowOfCubesAtTwoMillisecondsSubstep) {
  int runs = 0;
  const std::vector<std::string> off = cube_rows_at(0.002, 4, &runs);
  EXPECT_EQ(runs, 72);
  std::printf("[measured] %d sliders arriving on rows of cubes at 2 ms x 4, substep: %zu off\n", runs, off.size());
  for (const std::string& o : off) ADD_FAILURE() << o;
}

// KNOWN DEFECT: the cube-row class at 5 ms x 4 (72 runs): 12 off at model revision 2026-12-05.2
// (28 at .12.04.2 and .12.05.1), the 3 x 1.5 m slider on 0.1 m cubes (450 times a cube) and the
// 1 x 0.5 m one (50 times), 2-59 % off Eq. 4 with rows driven 0.2-15 m. More sweeps beside the
// heavy slider mend more (converge_heavy.hpp: 16 sweeps, 7 off; 32, 2 off) at a cost on Vajont's
// meshes (32 sweeps: section VII's first 10 s 23 % slower). Through `ddafit simulate` on the same
// class laid out by a probe script (not kept): at 2026-12-04.2, 27 off at 5 ms x 4 and 28 at
// 10 ms x 3 (Vajont's step), and as many with the impact groups switched off (an environment
// switch, not kept), so what is left is the sweeps'; at .12.05.2, 10 at 5 ms x 4 and 10 at 10 ms
// x 3, every one the 450-times slider (docs/theory.md §13, "Limits of the substep solver").
TEST(JointCrossingFreeRow, DISABLED_SlidersArrivingOnARowOfCubesAtFiveMillisecondsSubstep) {
  int runs = 0;
  const std::vector<std::string> off = cube_rows_at(0.005, 4, &runs);
  EXPECT_EQ(runs, 72);
  std::printf("[measured] %d sliders arriving on rows of cubes at 5 ms x 4, substep: %zu off\n", runs, off.size());
  for (const std::string& o : off) ADD_FAILURE() << o;
}

INSTANTIATE_TEST_SUITE_P(JointCrossing, FreeRowSolver, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

}  // namespace
}  // namespace ddafit
