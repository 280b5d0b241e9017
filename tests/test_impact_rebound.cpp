// Impacts into resting blocks are inelastic: nothing comes back. Both solvers take an impact
// as a perfectly inelastic impulse, so a block driven into blocks at rest may stop or carry
// them along, but it must not be thrown back: any backward speed is the overlaps' push-out,
// (implicit solver) the blocks' own elastic spring-back, and |g| dt, the finest speed a step
// resolves. Found on a row of blocks against a wall
// (tests/test_impact_depth.cpp: 83 % of the impact speed from the substep solver, 45 % from
// the implicit one until model revision 2026-11-27.8); swept here over the other shapes the
// same event takes in a slide: a block dropped onto a stack, a block driven into a row free to
// move, and slow impacts into the walled row and onto stacks, with 3, 6 and 10 struck blocks
// (stacks of 15 too). One sweep is a known defect (disabled, docs/verification.md, "Slow drops
// onto stacks"): the substep solver's slow drops onto stacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"
#include "forward/mirror.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

BlockInput box(const std::string& name, Vec2 centre, double w, double h, bool fixed) {
  const Vec2 d(0.5 * w, 0.5 * h);
  return verification::block(name,
                             {centre - d, centre + Vec2(d.x(), -d.y()), centre + d, centre + Vec2(-d.x(), d.y())},
                             fixed);
}

enum class Shape { Stack, FreeRow, WalledRow };

struct Case {
  Shape shape;
  double size;    // m, the striker is a square of this side
  double speed;   // m/s
  double ratio;   // the struck blocks' thickness along the impact over the striker's size
  int count;      // struck blocks
  double step;    // s
  int substeps;
  Integrator integrator;
  double gap = 0.001;  // m, between the striker and the struck blocks at t = 0
  double friction = 30.0;  // deg, on every interface
  bool mirrored = false;   // run as the scene's mirror image (forward/mirror.hpp), read back unmirrored
  bool reversed = false;   // the scene's blocks listed in the reverse order (the measure points are places)
};

std::string label(const Case& c) {
  const char* shape = c.shape == Shape::Stack ? "onto a stack of" : c.shape == Shape::FreeRow ? "into a free row of" : "into a walled row of";
  char text[200];
  std::snprintf(text, sizeof text, "%s: %g m block at %g m/s %s %d blocks %g m thick, friction %g deg, %g ms x %d",
                c.integrator == Integrator::Implicit ? "implicit" : "substep", c.size, c.speed, shape, c.count,
                c.ratio * c.size, c.friction, c.step * 1000, c.substeps);
  return std::string(text) + (c.mirrored ? ", mirrored" : "") + (c.reversed ? ", blocks listed in reverse" : "");
}

// The struck blocks rest on a fixed floor (a stack: one on another; a row: side by side, the
// walled one ending against a fixed wall). The striker starts 1 mm away moving at `speed`
// towards them (downward onto a stack): the floor's friction (30 deg, 5.7 m/s^2) would stop a
// slow striker before a longer gap (the default Case::gap, 1 mm). The history every step.
constexpr double kDensity = 2500.0;  // kg/m^3, every block

Scene scene_of(const Case& c) {
  Scene s = verification::rock_scene(kDensity, c.friction, 0.5, c.step, c.step);
  s.options.integrator = c.integrator;
  s.options.substeps = c.substeps;
  const double w = c.size, t = c.ratio * c.size;
  s.blocks.push_back(box("floor", {0.0, -0.5 * w}, 40.0 * w + 4.0 * c.count * t, w, true));
  BlockInput striker;
  if (c.shape == Shape::Stack) {
    for (int i = 0; i < c.count; ++i) {
      s.blocks.push_back(box("stack_" + std::to_string(i), {0.0, (i + 0.5) * t}, w, t, false));
      s.measure.push_back({"stack_" + std::to_string(i), {0.0, (i + 0.5) * t}});
    }
    striker = box("striker", {0.0, c.count * t + c.gap + 0.5 * w}, w, w, false);
    striker.velocity = Vec2(0.0, -c.speed);
  } else {
    double x = 0.5 * w + c.gap;
    for (int i = 0; i < c.count; ++i, x += t) {
      s.blocks.push_back(box("row_" + std::to_string(i), {x + 0.5 * t, 0.5 * w}, t, w, false));
      s.measure.push_back({"row_" + std::to_string(i), {x + 0.5 * t, 0.5 * w}});
    }
    if (c.shape == Shape::WalledRow) s.blocks.push_back(box("wall", {x + 0.5 * w, w}, w, 2.0 * w, true));
    striker = box("striker", {0.0, 0.5 * w}, w, w, false);
    striker.velocity = Vec2(c.speed, 0.0);
  }
  s.measure.insert(s.measure.begin(), {"striker", striker.polygon[0] + 0.5 * (striker.polygon[2] - striker.polygon[0])});
  s.blocks.push_back(striker);
  return s;
}

// The bounds, as a share of the impact speed v: 5 % for the substep solver's rigid blocks (the
// push-out of the overlaps the impact leaves), 10 % for the implicit solver's elastic ones (a
// 4 m block of 5 GPa springs back by 4-9 % of a 20 m/s impact, tests/test_impact_depth.cpp),
// and |g| dt / v besides: gravity adds |g| dt to every speed in a step, and the implicit
// solver takes an approach slower than that as resting contact (docs/theory.md §7a), so it is
// the finest speed a step resolves (2 % of a 5 m/s impact at 10 ms, a third of a 0.3 m/s
// one). Overlaps within the 1 % of the smaller block that Vajont's runs are held to.
double rebound_bound(Integrator i, double step, double speed) {
  return (i == Integrator::Implicit ? 0.10 : 0.05) + 9.81 * step / speed;
}
constexpr double kOverlapBound = 0.01;
// Free rows: the floor may take 10 % of the impact's momentum beyond its friction. The
// substep solver's impulses keep to Coulomb exactly (1e-15 measured); the implicit solver's
// sliding friction is tan(phi) times the previous open-close pass's normal force, and where
// a block wedges against the floor within a step (a square striker at 45 deg, its tipping
// limit, tilts up on its front corner) the normal force the friction used lags the one the
// step ends with: 3.6 % measured (a 1 m striker at 5 m/s into three 0.25 m blocks, 10 ms x 3;
// 7.5 % before revision 2026-12-02.4 redid a step whose frozen locks ended past their cap).
// More passes do not close it (20 passes: 21 % at .11.28). Until revision 2026-11-28.1: 197 %,
// rows jammed against the floor and thrown back.
constexpr double kMomentumBound = 0.10;

struct Sweep {
  int runs = 0;
  // The fastest speed back along the impact over the impact speed: of any block (the free
  // row: of the striker; the row's tall blocks topple forward and rock as they land).
  double worst_rebound = 0.0;
  double worst_excess = -1.0;  // the largest of rebound - rebound_bound
  double worst_overlap = 0.0;  // of the smaller block
  std::string worst_case;
  // Free rows: the most momentum along the impact the floor took beyond what its friction
  // can give, over the impact's momentum (momentum_beyond_friction).
  double worst_momentum = 0.0;
  std::string worst_momentum_case;
};

// The floor is the only body outside a free row and its striker, and Coulomb friction gives
// it a horizontal impulse of at most tan(phi) times its vertical one, which is the weight's
// M g t plus the mass's upward momentum: P_x(0) - P_x(t) <= tan(phi) (M g t + P_y(t)). The
// largest excess over a run, as a share of P_x(0). Every block carries one measure point, at
// its centroid (scene_of).
double momentum_beyond_friction(const Case& c, const std::vector<HistoryRow>& history) {
  const double striker = kDensity * c.size * c.size, block = kDensity * c.ratio * c.size * c.size;
  const double total = striker + c.count * block, mu = std::tan(c.friction * M_PI / 180.0);
  const double p0 = striker * c.speed;
  double worst = 0.0;
  for (std::size_t k = 0; k < history.size();) {
    const double t = history[k].time;
    Vec2 p = Vec2::Zero();
    for (; k < history.size() && history[k].time == t; ++k)
      p += (history[k].point == 0 ? striker : block) * history[k].velocity;
    worst = std::max(worst, (p0 - p.x() - mu * (total * 9.81 * t + p.y())) / p0);
  }
  return worst;
}

// A case's run, mirrored if it asks (its history read back as the unmirrored scene's).
SimulationResult run_case(const Case& c) {
  Scene scene = scene_of(c);
  if (c.reversed) std::reverse(scene.blocks.begin(), scene.blocks.end());
  if (c.mirrored) scene = mirrored_scene(scene);
  SimulationResult r = simulate(scene);
  if (c.mirrored) unmirror_history(r.history);
  return r;
}

Sweep sweep(Shape shape, Integrator integrator, std::initializer_list<double> speeds,
            std::initializer_list<int> counts, std::initializer_list<double> frictions, bool mirrored = false,
            bool reversed = false) {
  Sweep out;
  for (const double size : {1.0, 4.0})
    for (const double speed : speeds)
      for (const double ratio : {1.0, 0.25})
        for (const int count : counts)
          for (const double friction : frictions)
            for (const auto& [step, substeps] : {std::pair{0.01, 3}, std::pair{0.005, 4}}) {
              Case c{shape, size, speed, ratio, count, step, substeps, integrator};
              c.friction = friction;
              c.mirrored = mirrored;
              c.reversed = reversed;
              const SimulationResult r = run_case(c);
              const std::string text = label(c);
              EXPECT_EQ(r.summary.status, RunStatus::Completed) << text << ": " << r.summary.message;
              const Vec2 along = shape == Shape::Stack ? Vec2(0.0, -1.0) : Vec2(1.0, 0.0);
              double rebound = 0.0;
              for (const HistoryRow& h : r.history)
                if (h.point == 0 || shape != Shape::FreeRow) rebound = std::max(rebound, -h.velocity.dot(along));
              rebound /= speed;
              out.worst_excess = std::max(out.worst_excess, rebound - rebound_bound(integrator, step, speed));
              if (rebound > out.worst_rebound) out.worst_rebound = rebound, out.worst_case = text;
              out.worst_overlap = std::max(out.worst_overlap, r.summary.solver.worst_penetration_ratio);
              if (shape == Shape::FreeRow) {
                const double beyond = momentum_beyond_friction(c, r.history);
                if (beyond > out.worst_momentum) out.worst_momentum = beyond, out.worst_momentum_case = text;
              }
              ++out.runs;
            }
  std::printf("[measured] %d impacts: fastest rebound %.3g of the impact speed (%s), worst overlap %.3g, largest "
              "excess over the bound %.3g\n", out.runs, out.worst_rebound, out.worst_case.c_str(), out.worst_overlap,
              out.worst_excess);
  if (shape == Shape::FreeRow)
    std::printf("[measured] momentum the floor took beyond its friction: %.3g of the impact's (%s)\n",
                out.worst_momentum, out.worst_momentum_case.c_str());
  return out;
}

// Every run of the sweep completes, nothing comes back faster than the bound, and no overlap
// goes deeper than kOverlapBound.
// Free rows: the floor took no more momentum than its friction gives (kMomentumBound).
void expect_inelastic(Shape shape, Integrator integrator, std::initializer_list<double> speeds, int runs,
                      std::initializer_list<int> counts = {3, 6, 10}, std::initializer_list<double> frictions = {30.0},
                      bool mirrored = false, bool reversed = false) {
  const Sweep s = sweep(shape, integrator, speeds, counts, frictions, mirrored, reversed);
  EXPECT_EQ(s.runs, runs);
  EXPECT_LE(s.worst_excess, 0.0) << s.worst_case;
  EXPECT_LE(s.worst_overlap, kOverlapBound);
  EXPECT_LE(s.worst_momentum, kMomentumBound) << s.worst_momentum_case;
}

// A block falling onto a stack of blocks resting on the floor (1 and 4 m, at 2, 5 and
// 10 m/s; stacks of 3, 6 and 10 blocks as tall as it or a quarter as tall): 72 runs per
// solver. The implicit solver: 7.0 % worst (bound 10 % + |g| dt / v; 9.6 % before revision
// 2026-11-28.1, whose impulsive-stop rule, update_blocks.hpp, takes the spring-back of a
// block stopped within a step).
TEST(ImpactRebound, ABlockDroppedOntoAStackDoesNotBounceOffImplicit) {
  expect_inelastic(Shape::Stack, Integrator::Implicit, {2.0, 5.0, 10.0}, 72);
}

// The substep solver on stacks of 3 and 6 (48 runs): 5.3 % worst (bound 9.9 % there). Until model revision
// 2026-11-27.10 it threw the block back at up to 86 % of its impact speed (one drop stopped with
// "contacts are creating energy"): the next substep's warm start re-applied the impact's
// impulses to the stopped stack, and two sweeps could not take them back. Since .27.10 an
// impact's group is solved directly (forward/substep/converge_impacts.hpp); until .27.8 a
// quiet-start defect (AGivenVelocityWaitsForTheClock below) launched drops at up to 37 times
// the impact speed.
TEST(ImpactRebound, ABlockDroppedOntoAStackDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {2.0, 5.0, 10.0}, 48, {3, 6});
}

// Stacks of ten and fifteen (48 runs): 3.1 % worst (bound 5 % + |g| dt / v). Until model
// revision 2026-11-28.6 the drops onto ten came back at up to 12.3 % (a 4 m block at 2 m/s onto
// ten 4 x 1 m blocks, bound 9.9 %; the one disabled test of issue "Blocks slide across joints
// ..."): the impact's group was solved in the first step (the block stopped, 0.02 m/s); the next
// substep's warm start applied the impact's impulses again, and over the next two steps the
// column's two sweeps, each contact left just under the group's margins, rose to 0.25 m/s and
// fell back. Since .28.6 the group's blocks are held to a tighter margin for two steps after the
// impact (ImpactConvergence::settle_substeps). Columns of twenty and thirty: below.
TEST(ImpactRebound, ABlockDroppedOntoAStackOfTenDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {2.0, 5.0, 10.0}, 48, {10, 15});
}

// Columns of twenty (24 runs). Until model revision 2026-11-29.4 a 1 m block at 5 m/s onto
// twenty 0.25 m blocks came back at 49 % of its speed (bound 7 %), and 8 of these 24 beyond the
// bound: the impact's group stopped striker and column, and the next substep's warm start
// re-applied the impact's impulses to the column at rest. Since .29.4 the first warm start after
// an impact hands on only what each point carried into it (solve_contacts.hpp, warm_start):
// 5.5 % worst (a 1 m block at 5 m/s onto twenty 1 m blocks, 5 ms x 4; bound 6.0 %).
TEST(ImpactRebound, ABlockDroppedOntoAColumnOfTwentyDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {2.0, 5.0, 10.0}, 24, {20});
}

// KNOWN DEFECT: columns of thirty (24 runs): 3 beyond the bound at .29.4, all at 10 ms x 3 (a
// 4 m block at 2 m/s onto thirty 4 x 1 m blocks: 13.9 %, bound 9.9 %; 7 of 24 at .29.3). An
// impact group grows about two blocks a round and stops after ImpactConvergence::max_rounds (8);
// more rounds (16) made it worse (6 of 48 over, columns of 20 and 30). Traced 2026-12-02
// (docs/theory.md §13, "Tried 2026-12-02 and not kept"): after a settling group stops the moving
// column, the warm start hands on the weight less the braking (56 % at the floor), the column
// sinks, its groups are too large to solve, and a block is thrown up. Handing on a grounded
// group's resting impulses instead passes all 24 but fails a column of twenty and takes Vajont
// section VII degraded's worst overlap from 0.44 to 0.91 %.
TEST(ImpactRebound, DISABLED_ABlockDroppedOntoAColumnOfThirtyDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {2.0, 5.0, 10.0}, 24, {30});
}

// Slow drops: 0.4-1.5 m/s, from just above the speed a 10 ms step of three substeps starts an
// impact group at (10 |g| h = 0.33 m/s) to 1.5 times the |g| dt of a 10 ms step, onto stacks of
// 2-15 blocks, friction 15, 30 and 45 deg (600 runs per solver), where a step begins to take an
// approach as resting contact. The implicit solver: 22.4 % of 0.4 m/s worst (a 1 m block onto
// ten 0.25 m blocks at 45 deg, bound 10 % + |g| dt / v = 34.5 %).
TEST(ImpactRebound, ASlowBlockDroppedOntoAStackDoesNotBounceOffImplicit) {
  expect_inelastic(Shape::Stack, Integrator::Implicit, {0.4, 0.5, 0.7, 1.0, 1.5}, 600, {2, 3, 6, 10, 15},
                   {15.0, 30.0, 45.0});
}

// The substep solver, from 0.5 m/s onto stacks of 2-10 (384 runs): 18.7 % worst (a 4 m block at
// 0.5 m/s onto six 4 m blocks, 15 deg; bound 5 % + |g| dt / v = 24.6 %). Until model revision
// 2026-11-28.7 it threw slow drops back at up to 85 % of their speed (a 1 m block at 0.5 m/s onto
// ten 0.25 m blocks, 45 deg), and 47 % in the first, narrower sweep of this test (a 4 m block onto
// three 4 x 1 m blocks at 30 deg, bound 24.6 %): the two sweeps took the blow down the column and
// left every joint closing under the group trigger, so no group started, and the warm start of
// the next substeps re-applied the impulses that had stopped the striker to blocks at rest. Since
// .28.7 a block struck through a joint that carries weight is held to the settling margins
// (forward/substep/converge_impacts.cpp, mark_struck): 8.5 % worst at .29.2.
TEST(ImpactRebound, ASlowBlockDroppedOntoAStackDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.5, 0.7, 1.0, 1.5}, 384, {2, 3, 6, 10}, {15.0, 30.0, 45.0});
}

// The same, widened to the implicit test's 600 runs (0.4 m/s and stacks of fifteen): the struck
// rule of .28.7 left 2 over the bound (a 4 m block at 0.4 m/s onto six 1 m blocks at 15 deg,
// 39 %, bound 29.5 %: the speculative contact slowed it to its 1 mm gap's allowance in one
// substep and it met the stack under the margin in the next; a 1 m block at 0.5 m/s onto
// fifteen 0.25 m blocks at 45 deg, 32 %, bound 24.6 %). Since model revision 2026-11-28.8 a
// point is struck when its free approach beats the margin and closes its gap within the
// substep, and a settling column still solved at the tight margins is held for another step
// (18.3 % worst at .28.8; 9.7 % at .29.2, which marks a joint at a fifth of the impact margin).
TEST(ImpactRebound, ASlowBlockDroppedOntoATallStackDoesNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.4, 0.5, 0.7, 1.0, 1.5}, 600, {2, 3, 6, 10, 15},
                   {15.0, 30.0, 45.0});
}

// The class, on speeds, heights and frictions none of the sweeps above was tuned on (576 runs:
// 0.3-4 m/s, stacks of 3-13, 25 and 40 deg). At .28.7, 16 of them came back beyond the bound
// (63 % of 0.3 m/s worst); since .28.8 none (21.8 % worst at .29.2).
TEST(ImpactRebound, SlowDropsAtOtherSpeedsAndHeightsDoNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.3, 0.38, 0.55, 0.9, 1.7, 4.0}, 576, {3, 5, 7, 9, 11, 13},
                   {25.0, 40.0});
}

// A second untuned sweep (560 runs: 0.35-3 m/s, stacks of 2-15, 20 and 35 deg). 7 over the
// bound at .28.7 (one stopped by the energy audit), 1 at .28.8-.29.1: a 1 m block at 0.45 m/s
// onto twelve 0.25 m blocks at 35 deg came back at 44 % (bound 26.8 %): the column's top blocks
// hopped after the impact and landed again at 0.2 m/s, under the struck rule's margin then, and
// the sweeps and warm start threw the column up. Since .29.2 a joint struck at a fifth of the
// impact margin settles (converge_impacts.cpp, kStruckShare): 10.1 % worst.
TEST(ImpactRebound, SlowDropsOntoStacksSecondSweepDoNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.35, 0.45, 0.6, 0.8, 1.2, 2.0, 3.0}, 560, {2, 4, 8, 12, 15},
                   {20.0, 35.0});
}

// Third and fourth untuned sweeps, found 2026-11-29, reaching under the impact margin (0.33 m/s
// at 10 ms x 3): 576 runs (0.25-2.5 m/s, stacks of 3-14, 10/28/42 deg) and 448 (0.15-3.5 m/s,
// stacks of 2-11, 18/33 deg). At .29.1, 12 and 10 over their bound (95 % of 0.15 m/s onto
// eight 0.25 m blocks, bound 70 %); at .29.2 none (22.5 % and 33.8 % worst). The implicit
// solver, unchanged: none (34.1 % and 39.5 % worst).
TEST(ImpactRebound, DropsUnderTheImpactMarginDoNotBounceOffSubstep) {
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.25, 0.33, 0.5, 0.65, 1.1, 2.5}, 576, {3, 6, 9, 14},
                   {10.0, 28.0, 42.0});
  expect_inelastic(Shape::Stack, Integrator::Substep, {0.15, 0.2, 0.28, 0.42, 0.75, 1.3, 3.5}, 448, {2, 5, 8, 11},
                   {18.0, 33.0});
}

TEST(ImpactRebound, DropsUnderTheImpactMarginDoNotBounceOffImplicit) {
  expect_inelastic(Shape::Stack, Integrator::Implicit, {0.25, 0.33, 0.5, 0.65, 1.1, 2.5}, 576, {3, 6, 9, 14},
                   {10.0, 28.0, 42.0});
  expect_inelastic(Shape::Stack, Integrator::Implicit, {0.15, 0.2, 0.28, 0.42, 0.75, 1.3, 3.5}, 448, {2, 5, 8, 11},
                   {18.0, 33.0});
}

// A block driven into a row that nothing holds: the row is pushed along (its tall blocks
// topple), the striker is not thrown back, and the floor takes no more momentum than its
// friction gives (momentum_beyond_friction). Friction 30 and 45 deg (at 45 deg a square
// striker is at its tipping limit and tall blocks topple as they slide), 1-10 m/s: 192 runs.
// The substep solver: 6.7 % worst (a 4 m block at 1 m/s into six 1 m blocks, 45 deg, 5 ms x 4;
// bound 9.9 %; 4.0 % before revision 2026-11-28.6's settling of impact groups, 3.2 % before
// the 45 deg and 1 m/s cases were added; 0.2 % before the impact groups of .27.10, which solve
// the striker's impact inelastically in the substep it happens instead of over several).
TEST(ImpactRebound, ABlockDrivenIntoAFreeRowIsNotThrownBackSubstep) {
  expect_inelastic(Shape::FreeRow, Integrator::Substep, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0});
}

// The implicit solver: 5.4 % worst (a 1 m block at 5 m/s into three 0.25 m blocks, 45 deg,
// 5 ms x 4; bound 11 %); 11.1 % before revision 2026-12-02.4 (a 1 m block at 2 m/s into six
// 0.25 m blocks, 45 deg, 5 ms x 4: the striker tilted up on its front corner and rocked back;
// bound 12.5 %). Until
// revision 2026-11-28.1 it threw the striker back at up to 38 % of its speed at 30 deg (56 %
// at 45 deg): a closed point that the open-close iteration had frozen held 5 MN/m of tension
// (check_contacts.cpp), the locked floor points met the struck row's whole slip
// (new_points.hpp), the row jammed against the floor within a step and the velocity update
// V1 = 2 D / dt - V0 turned its motion round (update_blocks.hpp). Without any one of the
// three mends a wider sweep (blocks 0.15 m thick too) fails: without the opening rule 34 of
// 144 runs give the floor over 10 % beyond its friction, without the slides 6 (46 % worst),
// without the impulsive stop a striker comes back at 28 % of 1 m/s. (The slides, withdrawn
// at .28.2 because they tipped the implicit Vajont section I run over its energy audit, came
// back at .28.3 with the audit mended, tests/test_energy_audit.cpp.)
TEST(ImpactRebound, ABlockDrivenIntoAFreeRowIsNotThrownBackImplicit) {
  expect_inelastic(Shape::FreeRow, Integrator::Implicit, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0});
}

// Slow impacts into the walled row: 0.3 and 1 m/s, three and ten times the |g| dt of a 10 ms
// step, where both solvers begin to take an approach as an impact. 48 runs per solver. The
// implicit solver: 29 % of 0.3 m/s worst (0.088 m/s, under the |g| dt of 0.098 m/s; bound
// 10 % + |g| dt / v = 43 %; 21 % before revision 2026-11-28.1).
TEST(ImpactRebound, ASlowBlockDrivenIntoAWalledRowIsNotThrownBackImplicit) {
  expect_inelastic(Shape::WalledRow, Integrator::Implicit, {0.3, 1.0}, 48);
}

// The substep solver: 13.8 % of 0.3 m/s worst (bound 5 % + |g| dt / v = 21 % at 5 ms); until
// revision 2026-11-27.10, 41 % of 1 m/s (bound 15 %), the walled row's defect at slow speeds.
TEST(ImpactRebound, ASlowBlockDrivenIntoAWalledRowIsNotThrownBackSubstep) {
  expect_inelastic(Shape::WalledRow, Integrator::Substep, {0.3, 1.0}, 48);
}

// The rows mirrored (forward/mirror.hpp): the striker driven in from the right. The same
// physics, met in another order by the sweeps, the open-close iteration and the narrow
// phase's tie-breaks. Measured 2026-12-02: the implicit solver's 48 walled-row impacts within
// their bounds both ways round, and since revision 2026-12-02.4 its 192 free-row impacts too
// (below); the substep sweeps each have cases over their bound in the mirror only, known
// defects (docs/theory.md §13, "Limits of the substep solver"):
//   - substep, free row: 1 of 192, a 4 m block at 10 m/s into ten 1 m blocks at 45 deg,
//     10 ms x 3, comes back at 6.6 % of its speed (bound 6.0 %);
//   - substep, walled row: 1 of 48, a 4 m block at 1 m/s into three 4 m blocks, 10 ms x 3,
//     comes back at 15.4 % (bound 14.8 %).
TEST(ImpactRebound, ASlowBlockDrivenIntoAWalledRowMirroredIsNotThrownBackImplicit) {
  expect_inelastic(Shape::WalledRow, Integrator::Implicit, {0.3, 1.0}, 48, {3, 6, 10}, {30.0}, true);
}

TEST(ImpactRebound, DISABLED_ABlockDrivenIntoAFreeRowMirroredIsNotThrownBackSubstep) {
  expect_inelastic(Shape::FreeRow, Integrator::Substep, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0}, true);
}

// The implicit solver's free row mirrored: 3.7 % of the impact's momentum beyond the floor's
// friction worst (a 1 m block at 2 m/s into three 0.25 m blocks at 45 deg, 10 ms; bound 10 %),
// fastest rebound 6.6 % (bound 12 %). Until revision 2026-12-02.4, 45 % and 14.8 % (a 1 m
// block at 5 m/s into three 0.25 m blocks at 45 deg, 10 ms): the struck row tipped on the
// front block's leading corner, the open-close iteration reached its pass limit with frozen
// locked points on the floor and between the blocks carrying up to ten times their Coulomb
// cap (their normal forces fell twentyfold in the last pass), and the step was accepted; the
// whole row and the striker turned about that corner and leapt at 1.2 m/s. Such a step is now
// redone shorter (forward/step/judge_step.cpp, kCapExcessTolerance).
TEST(ImpactRebound, ABlockDrivenIntoAFreeRowMirroredIsNotThrownBackImplicit) {
  expect_inelastic(Shape::FreeRow, Integrator::Implicit, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0}, true);
}

TEST(ImpactRebound, DISABLED_ASlowBlockDrivenIntoAWalledRowMirroredIsNotThrownBackSubstep) {
  expect_inelastic(Shape::WalledRow, Integrator::Substep, {0.3, 1.0}, 48, {3, 6, 10}, {30.0}, true);
}

// The same scenes with their blocks listed in the reverse order (striker first, floor last):
// the same physics again, met in another order. Found 2026-12-02 by an exploratory build that
// reversed the blocks of every scene given as blocks and ran the whole suite. Known defect
// (substep, revision 2026-12-02.2): free rows 9.1 % of 2 m/s (4 m block, six 1 m blocks,
// 45 deg, 10 ms x 3; excess over the bound 0.018), walled rows 19.3 % of 1 m/s (1 m block,
// three 0.25 m blocks, 10 ms x 3; excess 0.045), columns of twenty 9.5 % of 10 m/s (excess
// 0.040). The implicit solver passes since revision 2026-12-02.4 (free rows: 4.7 % of the
// impact's momentum beyond the floor's friction, rebound 5.8 %; 45 % before, as in the mirror).
// Elsewhere in the suite listed in reverse: tests/test_impact_depth.cpp's implicit rows rebound at
// 10.03 % (bound 10 %) and the 100-brick standing wall of tests/test_stability.cpp needs one
// step cut (none listed as built); every other enabled test passes.
TEST(ImpactRebound, DISABLED_ImpactsWithTheBlocksListedInReverseDoNotBounceOffSubstep) {
  expect_inelastic(Shape::FreeRow, Integrator::Substep, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0}, false,
                   true);
  expect_inelastic(Shape::WalledRow, Integrator::Substep, {0.3, 1.0}, 48, {3, 6, 10}, {30.0}, false, true);
  expect_inelastic(Shape::Stack, Integrator::Substep, {2.0, 5.0, 10.0}, 24, {20}, {30.0}, false, true);
}

TEST(ImpactRebound, ImpactsWithTheBlocksListedInReverseDoNotBounceOffImplicit) {
  expect_inelastic(Shape::FreeRow, Integrator::Implicit, {1.0, 2.0, 5.0, 10.0}, 192, {3, 6, 10}, {30.0, 45.0}, false,
                   true);
  expect_inelastic(Shape::WalledRow, Integrator::Implicit, {0.3, 1.0}, 48, {3, 6, 10}, {30.0}, false, true);
}

// A velocity given to a block waits for the clock (the quiet start settles the touching blocks
// at rest, forward/substep/run_substep.cpp): the state at t = 0 cannot depend on it. Found on
// the substep solver (revision 2026-11-27.8 and before): a striker within the contact margin
// of a stack but not touching it was held still with its velocity kept, so its contact pressed
// the stack down through the whole quiet start (5.6 mm for 2 m/s at a 1 mm gap) and the
// impulses that built up launched stack and striker at the first step (27 of the 48 drops
// stopped with "contacts are creating energy"). Gaps inside the margin, speeds, sizes, both
// solvers: every stack block's position at t = 0 is the same as with the striker at rest, to
// 1e-9 m (the same computation, so only rounding may differ).
TEST(ImpactRebound, AGivenVelocityWaitsForTheClock) {
  for (const Integrator integrator : {Integrator::Substep, Integrator::Implicit})
    for (const double gap : {0.0002, 0.001, 0.003})
      for (const double size : {1.0, 4.0})
        for (const double speed : {2.0, 10.0}) {
          Case c{Shape::Stack, size, speed, 0.25, 3, 0.01, 3, integrator, gap};
          Scene moving = scene_of(c);
          moving.duration = c.step;  // the t = 0 row is what is asserted
          Scene resting = scene_of(c);
          resting.blocks.back().velocity = Vec2::Zero();  // the striker, at rest
          resting.duration = c.step;
          const SimulationResult a = simulate(moving), b = simulate(resting);
          ASSERT_FALSE(a.history.empty());
          ASSERT_FALSE(b.history.empty());
          double worst = 0.0;
          for (size_t i = 0; i < a.history.size() && i < b.history.size(); ++i)
            if (a.history[i].time == 0.0 && a.history[i].point > 0)
              worst = std::max(worst, (a.history[i].position - b.history[i].position).norm());
          EXPECT_LE(worst, 1e-9) << label(c) << ", gap " << gap * 1000 << " mm";
        }
}

}  // namespace
}  // namespace ddafit
