// A fast block stopped by a contact must stop at the contact. Found on Vajont section VII
// degraded with split impulses (model revision 2026-11-27.3): a block rotating into its
// neighbour at 14 m/s was stopped by the contact, but the substep's trapezoidal move
// h (v0 + v1) / 2 still carried it h |v0| / 2 = 2 cm into the neighbour, 1 % of the smaller
// block. Since .27.4 the move after an impact follows the velocity after it (docs/theory.md
// §13, "Split impulses", step 5). Swept over block sizes, speeds, steps and what is hit (the
// fixed floor, a resting block as large, a resting block a quarter as large), square-on and
// corner first, because the depth an impact reaches depends on where within a substep the
// contact is met; and on both solvers (the implicit solver's impacts are impulses too,
// forward/step/resolve_impacts.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

// A w x h box centred at `centre`, turned by `angle` (radians).
BlockInput box(const std::string& name, Vec2 centre, double w, double h, double angle, bool fixed) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> corners;
  for (const Vec2& p : {Vec2(-0.5 * w, -0.5 * h), Vec2(0.5 * w, -0.5 * h), Vec2(0.5 * w, 0.5 * h), Vec2(-0.5 * w, 0.5 * h)})
    corners.push_back(centre + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
  return verification::block(name, corners, fixed);
}

enum class Target { Floor, SameSize, Quarter };

struct Impact {
  double size;      // m, the falling block is size x size / 2
  double speed;     // m/s, downward at the start, 0.5 m above what it hits
  double step;      // s
  int substeps;
  Target target;
  bool corner_first;  // turned 20 degrees: a corner meets the target first
  Integrator integrator;
};

const char* solver_name(Integrator i) { return i == Integrator::Implicit ? "implicit" : "substep"; }

std::string label(const Impact& c) {
  const char* target = c.target == Target::Floor ? "the floor" : c.target == Target::SameSize ? "a block as large" : "a quarter-size block";
  char text[160];
  std::snprintf(text, sizeof text, "%s: %g m block at %g m/s onto %s, %g ms x %d%s", solver_name(c.integrator), c.size,
                c.speed, target, c.step * 1000, c.substeps, c.corner_first ? ", corner first" : "");
  return text;
}

Scene impact_scene(const Impact& c) {
  Scene s = verification::rock_scene(2500.0, 30.0, 0.5, c.step, 0.05);
  s.options.integrator = c.integrator;
  s.options.substeps = c.substeps;
  const double w = c.size;
  s.blocks.push_back(box("floor", {0.0, -0.5 * w}, 8.0 * w, w, 0.0, true));
  double top = 0.0;  // m, the height of what the block falls onto
  if (c.target != Target::Floor) {
    const double tw = c.target == Target::SameSize ? w : 0.25 * w;
    s.blocks.push_back(box("target", {0.0, 0.25 * tw}, tw, 0.5 * tw, 0.0, false));
    top = 0.5 * tw;
  }
  const double angle = c.corner_first ? 20.0 * M_PI / 180.0 : 0.0;
  // The lowest point of the turned block 0.5 m above the target.
  const double reach = 0.5 * (w * std::sin(angle) + 0.5 * w * std::cos(angle));
  BlockInput falling = box("falling", {0.0, top + 0.5 + reach}, w, 0.5 * w, angle, false);
  falling.velocity = Vec2(0.0, -c.speed);
  s.blocks.push_back(falling);
  s.measure.push_back({"falling", {0.0, top + 0.5 + reach}});
  return s;
}

// The deepest overlap stays within 0.5 % of the smaller block: a tenth of what the plain
// trapezoid gave Vajont's impact, and above the slop (1e-3 of a step's largest move) and the
// h^2 g that the rule still lets a stopped block move (at most 0.1 mm here).
constexpr double kMaxImpactOverlap = 0.005;

// Runs every impact of the sweep onto `targets`; returns how many ran.
int run_impacts(std::initializer_list<Target> targets, double max_overlap) {
  int runs = 0;
  double worst = 0.0;
  std::string worst_case;
  for (const double size : {1.0, 4.0, 8.0})
    for (const double speed : {5.0, 10.0, 20.0})
      for (const auto& [step, substeps] : {std::pair{0.01, 3}, std::pair{0.005, 4}})
        for (const Target target : targets)
          for (const bool corner : {false, true})
            for (const Integrator integrator : {Integrator::Substep, Integrator::Implicit}) {
            const Impact c{size, speed, step, substeps, target, corner, integrator};
            const SimulationResult r = simulate(impact_scene(c));
            EXPECT_EQ(r.summary.status, RunStatus::Completed) << label(c) << ": " << r.summary.message;
            EXPECT_LE(r.summary.solver.worst_penetration_ratio, max_overlap)
                << label(c) << ": " << r.summary.solver.worst_penetration << " m between "
                << r.summary.solver.worst_penetration_at;
            if (r.summary.solver.worst_penetration_ratio > worst)
              worst = r.summary.solver.worst_penetration_ratio, worst_case = label(c);
            ++runs;
          }
  std::printf("[measured] worst overlap %.4g of the smaller block (%s)\n", worst, worst_case.c_str());
  return runs;
}

// Onto the fixed floor and onto a resting block as large: 72 impacts per solver. With the
// trapezoidal move of revision .27.3 (kSmoothAccelerationRatio 0) 7 substep runs overlapped
// by more than 0.5 %, up to 1.01 % (a 1 m block at 10-20 m/s).
TEST(ImpactDepth, AFastBlockStopsAtWhatItHits) {
  EXPECT_EQ(run_impacts({Target::Floor, Target::SameSize}, kMaxImpactOverlap), 144);
}

// A light block squeezed between a heavy one arriving fast and the fixed floor (mass ratio
// 16): held within 1 % of its size, the bound Vajont's runs are held to. Gauss-Seidel gains
// ~1/(1 + mass ratio) of the error per sweep, so the sweeps leave it sinking; the step's
// position correction takes it out. Until revision 2026-11-27.6 the correction stopped after
// eight passes while a pass was still correcting: up to 1.9 % (1 m block at 20 m/s onto a
// 0.25 m one, 10 ms x 3; 14 of 36 above 0.5 %). With up to sixteen while one still corrects,
// 0.67 % (2 of 36 above 0.5 %, the bound of the impacts above; not reached here).
TEST(ImpactDepth, ALightBlockSqueezedOntoTheFloorStaysOutOfIt) {
  EXPECT_EQ(run_impacts({Target::Quarter}, 2.0 * kMaxImpactOverlap), 72);
}

// A block sliding at `speed` along the floor into a row of `count` resting blocks that ends
// against a fixed wall. The striker is a square of side `size`; the row's blocks are as tall
// and `ratio` times as wide (mass ratio 1 / ratio). The first is squeezed between the
// striker and the second, which the sweeps of the first's deep manifolds drive into the
// third, whose manifold they do not list. A measure point at every block's centre.
struct RowImpact {
  double size, speed, ratio;
  int count;
  double step;
  int substeps;
  double output;  // s, the history's interval (a shorter one than the step shortens the step)
  Integrator integrator;
};

Scene row_scene(const RowImpact& c) {
  Scene s = verification::rock_scene(2500.0, 30.0, 0.5, c.step, c.output);
  s.options.integrator = c.integrator;
  s.options.substeps = c.substeps;
  const double w = c.size, r = c.ratio * c.size;
  s.blocks.push_back(box("floor", {0.0, -0.5 * w}, 8.0 * w + 2.0 * c.count * r, w, 0.0, true));
  s.measure.push_back({"striker", {0.0, 0.5 * w}});
  double x = 0.5 * w + 0.5;  // the striker's face at 0.5 w, the row 0.5 m beyond it
  for (int i = 0; i < c.count; ++i, x += r) {
    s.blocks.push_back(box("row_" + std::to_string(i), {x + 0.5 * r, 0.5 * w}, r, w, 0.0, false));
    s.measure.push_back({"row_" + std::to_string(i), {x + 0.5 * r, 0.5 * w}});
  }
  s.blocks.push_back(box("wall", {x + 0.5 * w, w}, w, 2.0 * w, 0.0, true));
  BlockInput striker = box("striker", {0.0, 0.5 * w}, w, w, 0.0, false);
  striker.velocity = Vec2(c.speed, 0.0);
  s.blocks.push_back(striker);  // last: the order the sweeps meet the blocks in changes the numbers
  return s;
}

struct RowResults {
  int runs = 0;
  double worst_overlap = 0.0;  // of the smaller block
  double worst_rebound[2] = {0.0, 0.0};  // per solver (substep, implicit): fastest backward
                                         // speed of any block over the impact speed
};

// Runs the sweep over striker sizes (1, 4 m), speeds (5, 10, 20 m/s), row lengths (3, 6)
// and the time settings `steps` (by default the Vajont scene's two, the history written every
// step) for each row width in `ratios`, on each of `solvers`.
struct StepSetting {
  double step;
  int substeps;
  double output;
};
using Steps = std::initializer_list<StepSetting>;
constexpr Steps kVajontSteps = {{0.01, 3, 0.01}, {0.005, 4, 0.005}};

using Solvers = std::initializer_list<Integrator>;
constexpr Solvers kBothSolvers = {Integrator::Substep, Integrator::Implicit};

RowResults run_rows(std::initializer_list<double> ratios, bool check_reach, Steps steps = kVajontSteps,
                    Solvers solvers = kBothSolvers) {
  RowResults out;
  for (const double size : {1.0, 4.0})
    for (const double speed : {5.0, 10.0, 20.0})
      for (const double ratio : ratios)
        for (const int count : {3, 6})
          for (const auto& [step, substeps, output] : steps)
            for (const Integrator integrator : solvers) {
            const RowImpact c{size, speed, ratio, count, step, substeps, output, integrator};
            const SimulationResult r = simulate(row_scene(c));
            char text[180];
            std::snprintf(text, sizeof text, "%s: %g m block at %g m/s into %d blocks %g m wide, %g ms x %d, output every %g ms",
                          solver_name(integrator), size, speed, count, ratio * size, step * 1000, substeps, output * 1000);
            EXPECT_EQ(r.summary.status, RunStatus::Completed) << text << ": " << r.summary.message;
            EXPECT_LE(r.summary.solver.worst_penetration_ratio, 2.0 * kMaxImpactOverlap)
                << text << ": " << r.summary.solver.worst_penetration << " m between " << r.summary.solver.worst_penetration_at;
            // The striker meets the row 0.5 m away and the row, held by the wall, stops it: it
            // goes no further than 0.5 m and the allowed overlaps (1 % of each row block). (Its
            // |u_x| is no measure: it comes back, see the disabled test below.)
            double reach = 0.0;
            for (const HistoryRow& h : r.history) {
              if (h.point == 0) reach = std::max(reach, h.displacement.x());
              double& rebound = out.worst_rebound[integrator == Integrator::Implicit];
              rebound = std::max(rebound, -h.velocity.x() / speed);
            }
            if (check_reach) {
              EXPECT_GE(reach, 0.49) << text;
              EXPECT_LE(reach, 0.5 + 2.0 * kMaxImpactOverlap * count * ratio * size) << text;
            }
            out.worst_overlap = std::max(out.worst_overlap, r.summary.solver.worst_penetration_ratio);
            ++out.runs;
          }
  std::printf("[measured] %d row impacts: worst overlap %.4g of the smaller block, fastest rebound (of the impact "
              "speed)", out.runs, out.worst_overlap);
  for (const Integrator i : solvers)
    std::printf(" %s %.3g", solver_name(i), out.worst_rebound[i == Integrator::Implicit]);
  std::printf("\n");
  return out;
}

// Since revision 2026-11-27.7 the extra sweeps bring in a block they drive deep (docs/
// theory.md §13, "Extra sweeps for deep manifolds"); found on Vajont section X reference,
// where a 1.8 m block was driven at 13 m/s into an unlisted neighbour, 1.02 % of its size.
// A row of blocks as large as the striker: held to the 1 % Vajont is held to, the striker
// stopped where the row stands. Measured 0.40 % worst; revision .27.6 (converge_deep without
// the far blocks) holds these 24 as well: the test guards the class of the event, which has
// so far gone deep only on Vajont section X. The implicit solver (24 runs more) was added at
// .27.8: 1.09 % before its impacts took in the row (below), 0.89 % after.
TEST(ImpactDepth, ABlockDrivenIntoARowAgainstAWallStaysOutOfItsNeighbours) {
  EXPECT_EQ(run_rows({1.0}, true).runs, 48);
}

// The contact is inelastic (both solvers take impacts as perfectly inelastic impulses), so
// nothing should come back faster than the little the overlaps' push-out gives: 5 % of the
// impact speed for rigid contact; the implicit solver's blocks are elastic and get 10 %.
// Rows as wide as the striker and a quarter as wide (mass ratio 4), and 10 ms steps cut to
// 5 ms by a 5 ms history besides the Vajont steps: 72 runs per solver.
constexpr Steps kRowSteps = {{0.01, 3, 0.01}, {0.005, 4, 0.005}, {0.01, 3, 0.005}};

// The implicit solver threw blocks back at up to 45 % until revision 2026-11-27.8: its
// impact impulses (forward/step/resolve_impacts.cpp) took only the points closing at the
// step's start, so the row's resting contacts met the struck block at their penalty
// springs, which hand the approach back (V1 = 2 D / dt - V0). Since .27.8 a group closing
// faster than |g| dt converges and the points its impulses set closing join it: 8.9 % worst;
// 8.0 % since .28.1 (no closed point held in tension, test_impact_rows.cpp's free rows).
// The rest is the blocks' own elasticity
// (Shi's strain unknowns; the impulses move the blocks' rigid part only): with E 100 times
// the 5 GPa here, 4.1 %. Hence twice the rigid bound, for the spring-back of elastic blocks.
TEST(ImpactDepth, TheImplicitSolversRowDoesNotThrowTheStrikerBack) {
  const RowResults rows = run_rows({1.0, 0.25}, false, kRowSteps, {Integrator::Implicit});
  EXPECT_EQ(rows.runs, 72);
  EXPECT_LE(rows.worst_rebound[1], 0.10);
}

// The substep solver's rows (72 runs, bound 5 %): 4.3 % worst since model revision
// 2026-11-27.10. Before it, 22 % of the impact speed from rows as large as the striker and
// 83 % from quarter-width rows, and with the history every 5 ms a 1 m block at 10 m/s into six
// of those stopped with "contacts are creating energy": the next substep's warm start
// re-applied the impact's impulses to blocks that had stopped, and two Gauss-Seidel sweeps
// could not unwind them along the row to the wall. Now the points an impact leaves closing, or
// pushing apart blocks that separate, are solved as one group directly
// (forward/substep/converge_impacts.hpp). Measured mends, none kept: the warm start allowed to
// grow by at most 4 |g| h of a point's effective mass per substep: 2.0 % here, but Vajont's
// overlaps rose (section IV degraded 0.55 -> 1.15 %); with extra sweeps on every capped
// manifold 0.96 % but 34 % more wall; no warm start 0.1 % (resting masses sink); 8 / 32 / 128
// sweeps over every manifold 33 / 15.5 / 6.6 %; the warm start of a whole group of touching
// blocks scaled to its least kinetic energy (branch spent-impacts): 3.0 %, but Vajont VI-VIII
// took 2.5-3 x the wall and their deposits rattled (docs/verification.md has the table).
TEST(ImpactDepth, TheSubstepSolversRowDoesNotThrowTheStrikerBack) {
  const RowResults rows = run_rows({1.0, 0.25}, false, kRowSteps, {Integrator::Substep});
  EXPECT_LE(rows.worst_rebound[0], 0.05);
}

}  // namespace
}  // namespace ddafit
