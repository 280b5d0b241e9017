// Impacts into rows of resting blocks are inelastic too (tests/test_impact_rebound.cpp has the
// stacks and the reasons): a block driven into a row free to move along the floor, and slow
// impacts into a row that ends against a fixed wall; as built, mirrored (the striker driven in
// from the right, forward/mirror.hpp) and with the scene's blocks listed in reverse. The
// substep solver's mirrored free rows and reversed sweeps are known defects (disabled; docs/theory.md
// §13, "Limits of the substep solver").
#include <gtest/gtest.h>

#include <vector>

#include "tests/impact_sweep.hpp"

namespace ddafit {
namespace {

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
//     came back at 15.4 % (bound 14.8 %); since model revision 2026-12-05.9 (overlaps
//     corrected from 2.5e-4 of a block in scenes this small, control.deep_overlap_ratio) all 48
//     are within their bounds (worst 27.9 % of 0.3 m/s, 0.016 under its bound), enabled below.
TEST(ImpactRebound, ASlowBlockDrivenIntoAWalledRowMirroredIsNotThrownBackImplicit) {
  expect_inelastic(Shape::WalledRow, Integrator::Implicit, {0.3, 1.0}, 48, {3, 6, 10}, {30.0}, true);
}

// Re-measured at model revision 2026-12-06.20: 1 of 192 over, a 4 m block at 1 m/s into ten 1 m
// blocks at 45 deg, 5 ms x 4, comes back at 8.4 % of its speed (excess over its bound 0.005).
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

TEST(ImpactRebound, ASlowBlockDrivenIntoAWalledRowMirroredIsNotThrownBackSubstep) {
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
// step cut (none listed as built); every other enabled test passes. Re-measured at model revision
// 2026-12-06.20: the free rows (192, fastest rebound 5.2 %) and the walled rows (48, 32.9 % of
// 0.3 m/s) are within their bounds; the columns of twenty are not, a 4 m block at 5 m/s onto
// twenty 4 m blocks, 5 ms x 4, comes back at 9.1 % (excess 0.031).
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

}  // namespace
}  // namespace ddafit
