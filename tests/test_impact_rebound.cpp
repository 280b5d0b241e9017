// Impacts into resting blocks are inelastic: nothing comes back. Both solvers take an impact
// as a perfectly inelastic impulse, so a block driven into blocks at rest may stop or carry
// them along, but it must not be thrown back: any backward speed is the overlaps' push-out,
// (implicit solver) the blocks' own elastic spring-back, and |g| dt, the finest speed a step
// resolves. Found on a row of blocks against a wall
// (tests/test_impact_depth.cpp: 83 % of the impact speed from the substep solver, 45 % from
// the implicit one until model revision 2026-11-27.8); swept here over the other shapes the
// same event takes in a slide: a block dropped onto a stack, a block driven into a row free to
// move, and slow impacts into the walled row and onto stacks, with 3, 6 and 10 struck blocks
// (stacks of 15 too). This file has the stacks; tests/test_impact_rows.cpp the rows; the sweep
// and its bounds are in tests/impact_sweep.hpp. Two stack sweeps are known defects (disabled):
// the substep solver's drops onto columns of thirty, and its tall stacks' coming to rest after a
// drop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/impact_sweep.hpp"

namespace ddafit {
namespace {

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

// After the drop, the stack comes to rest. The sweeps above watch the first 0.5 s; a stack
// left standing must also stop moving, as a slide's deposit must. 256 drops (1 and 4 m strikers
// at 0.25-2.5 m/s onto stacks of 3-14 blocks as thick as the striker or a quarter of it, 28 and
// 42 deg, 10 ms x 3 and 5 ms x 4), each run for 3 s: the fastest point over the last half-second
// is held to 0.01 m/s (a tenth of the default rest_speed, the resting columns' bound).
struct Settling {
  int runs = 0;
  int moving = 0;        // runs whose last half-second is not at rest
  double worst = 0.0;    // m/s
  std::string worst_case;
};

Settling settle_after_drops(Integrator integrator) {
  Settling out;
  for (const double size : {1.0, 4.0})
    for (const double speed : {0.25, 0.5, 1.1, 2.5})
      for (const double ratio : {1.0, 0.25})
        for (const int count : {3, 6, 10, 14})
          for (const double friction : {28.0, 42.0})
            for (const auto& [step, substeps] : {std::pair{0.01, 3}, std::pair{0.005, 4}}) {
              Case c{Shape::Stack, size, speed, ratio, count, step, substeps, integrator};
              c.friction = friction;
              Scene scene = scene_of(c);
              scene.duration = 3.0;
              const SimulationResult r = simulate(scene);
              EXPECT_EQ(r.summary.status, RunStatus::Completed) << label(c) << ": " << r.summary.message;
              double last = 0.0;
              for (const HistoryRow& h : r.history)
                if (h.time >= scene.duration - 0.5) last = std::max(last, h.velocity.norm());
              ++out.runs;
              if (last >= 0.01) ++out.moving;
              if (last > out.worst) out.worst = last, out.worst_case = label(c);
            }
  std::printf("[measured] %d drops, %d still moving after 3 s; fastest over the last half-second %.3g m/s (%s)\n",
              out.runs, out.moving, out.worst, out.worst_case.c_str());
  return out;
}

// The implicit solver: every stack at rest, 2.2e-3 m/s at most (a 4 m block at 2.5 m/s onto
// fourteen 4 m blocks, 5 ms).
TEST(ImpactRebound, AStruckStackComesToRestImplicit) {
  const Settling s = settle_after_drops(Integrator::Implicit);
  EXPECT_EQ(s.runs, 256);
  EXPECT_LT(s.worst, 0.01) << s.worst_case;
}

// KNOWN DEFECT (found 2026-12-02, revision .12.02.4): the substep solver leaves 82 of the 256
// stacks rocking (all but one of 10 and 14 blocks; 0.42 m/s worst, a 1 m block at 2.5 m/s onto
// fourteen 0.25 m blocks at 10 ms x 3). Traced on a 1 m block at 1.1 m/s onto fourteen 0.25 m
// blocks (28 deg, 10 ms x 3): the stack rocks as one about its base (lateral speed linear in
// height, 0.18 m/s at the top, +-4.5 cm) for 5 s without decaying, and the centroids' kinetic
// plus potential energy rises by up to 530 J/m within 0.6 s (t = 0.7-1.3 s; the whole stack
// lifted 4.8 mm), of which the push-out's lift is 32 J/m. The velocity-level solve feeds it,
// in smooth stretches between impacts: there the warm start adds up to 8 J/m of kinetic energy
// per substep and the two relax sweeps take back 0.1-0.3 J/m. The energy audit
// does not stop it: the striker's 1512 J/m of kinetic energy at t = 0 stays in its allowance.
// Eight substeps instead of three leave 29 rocking, 0.087 m/s worst (docs/theory.md §13,
// "Limits of the substep solver").
TEST(ImpactRebound, DISABLED_AStruckStackComesToRestSubstep) {
  const Settling s = settle_after_drops(Integrator::Substep);
  EXPECT_EQ(s.runs, 256);
  EXPECT_LT(s.worst, 0.01) << s.worst_case;
}

// Impacts under a step control that cuts the step hard: control.max_displacement_ratio 2e-4 and
// 5e-5 of the half model size (4-6 mm and 1-1.6 mm of travel per step on these scenes), so a
// striker at 10 m/s steps 0.1-0.4 ms instead of the scene's 5 or 10 ms. The substep solver's
// impact margins scale with the substep it runs (|g| h, advance_step.cpp), so such steps leave
// them a hundredth of the scene's: the sweeps' ordinary residuals count as impacts (131 impact
// groups for a 1 m block at 10 m/s onto three 0.25 m blocks at 5e-5, against 4 at the default),
// as they did on the slivers cut to land on an output (revision 2026-12-03.6,
// tests/test_stacked_slider.cpp). Nothing may bounce off for it. Stacks, free rows and walled
// rows on both solvers, 192 runs at each ratio, under the bounds of impact_sweep.hpp (which keep the
// scene's step in |g| dt / v). Measured 2026-12-04: substep worst 5.4 % (a 1 m block at 10 m/s
// onto three 0.25 m blocks, 10 ms x 3, 5e-5; bound 6.0 %), free rows 4.1 %, walled rows 23 % of
// 0.3 m/s (bound 38 %); implicit 4.4 %, 3.4 % and 21 %, the floor taking at most 1.8 % of the
// impact's momentum beyond its friction.
void expect_inelastic_under_hard_step_control(Integrator integrator) {
  for (const double ratio : {2e-4, 5e-5}) {
    expect_inelastic(Shape::Stack, integrator, {2.0, 5.0, 10.0}, 48, {3, 6}, {30.0}, false, false, ratio);
    expect_inelastic(Shape::FreeRow, integrator, {2.0, 5.0, 10.0}, 72, {3, 6, 10}, {30.0}, false, false, ratio);
    expect_inelastic(Shape::WalledRow, integrator, {0.3, 1.0, 5.0}, 72, {3, 6, 10}, {30.0}, false, false, ratio);
  }
}

TEST(ImpactRebound, ImpactsUnderAHardStepControlDoNotBounceOffSubstep) {
  expect_inelastic_under_hard_step_control(Integrator::Substep);
}

TEST(ImpactRebound, ImpactsUnderAHardStepControlDoNotBounceOffImplicit) {
  expect_inelastic_under_hard_step_control(Integrator::Implicit);
}

// The walled rows again, the wall and the floor one L-shaped fixed block: its foot is a reflex
// corner of the ground (docs/theory.md §3, "Reflex corners"), where a slide meets the opposite
// bank. Found 2026-12-06 (revision .25): on the substep solver a 4 m block at 1 m/s into six 4 m
// blocks at max_displacement_ratio 5e-5 throws the whole row back, the striker at 0.214 of the
// impact speed against the bound's 0.148 (0.123 with the wall a block of its own). A known
// defect (docs/verification.md, "Kinks of the ground"): the substep test is disabled.
void expect_inelastic_against_one_ground(Integrator integrator) {
  for (const double ratio : {2e-4, 5e-5})
    expect_inelastic(Shape::WalledRowOneGround, integrator, {0.3, 1.0, 5.0}, 72, {3, 6, 10}, {30.0}, false, false,
                     ratio);
}

TEST(ImpactRebound, ImpactsIntoTheFootOfOneGroundUnderAHardStepControlDoNotBounceOffImplicit) {
  expect_inelastic_against_one_ground(Integrator::Implicit);
}

TEST(ImpactRebound, DISABLED_ImpactsIntoTheFootOfOneGroundUnderAHardStepControlDoNotBounceOffSubstep) {
  expect_inelastic_against_one_ground(Integrator::Substep);
}

}  // namespace
}  // namespace ddafit
