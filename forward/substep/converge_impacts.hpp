// Stage 4b of a substep (split impulses), after the two velocity sweeps: impacts solved where
// they happen. Gauss-Seidel hands an impulse on by about one contact per colour per sweep, so
// two sweeps leave an impact into a chain of blocks unconverged (a row driven against a wall, a
// stack a block lands on): blocks still closing on each other, and at the next substep the
// warm start re-applies the impact's impulses to blocks that have since stopped, throwing the
// striker back (83 % of its impact speed from a walled row; a block dropped on a stack came
// back at 86 %; tests/test_impact_depth.cpp, tests/test_impact_rebound.cpp). More sweeps do not
// cure it (40 sweeps per substep: still 14 %). This stage finds the points that break the
// normal contact's complementarity by an impact's margin after the sweeps, still closing into
// contact (faster than `closing`) or pushing apart blocks that separate (faster than `spent`:
// a spent impulse the warm start brought back), and solves each group of them, with every
// other manifold of their blocks, directly (docs/theory.md §13c).
#pragma once

#include <limits>
#include <vector>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

struct ImpactConvergence {
  double closing = 0.0;  // m/s: a point closing faster than this beyond its gap is an impact
  double spent = 0.0;    // m/s: a pushing point opening faster than this carries a spent impulse
  // A group is solved directly up to this many contact points (a dense solve); larger ones keep
  // the sweeps' answer. 160: rows and stacks of ten blocks with their floor and the manifolds
  // within the contact margin (tests/test_impact_rows.cpp; a walled row of ten 0.25 m blocks
  // struck at 10 m/s threw the striker back at 1.5 m/s with a cap of 40). Vajont section VII
  // degraded: 368,001 groups solved, 121,567 larger (docs/performance.md).
  int max_points = 160;
  // Rounds of taking in the neighbouring manifolds a solve left open: a stack of ten needed
  // more than four (at four a dropped block came back at 19 %).
  int max_rounds = 8;
  // Substeps after an impact in which its group's blocks are held to a tighter margin (a share
  // of `closing` and `spent`, converge_impacts.cpp): two steps' worth (advance_step.cpp). After a
  // direct solve the warm start brings the impact's impulses back, and the two sweeps leave every
  // contact of a tall stack just under the trigger while the errors add up the column: a block
  // dropped on a stack of ten came back at 12.3 % of its speed; held for one step, 8.5 % (on
  // fifteen), for two 3.1 % (tests/test_impact_rebound.cpp). Handing on, instead, the impulses
  // that hold the group at rest (a second complementarity solve) gave 2.6 % but doubled section
  // VII's wall, and a resting solve cut short created energy there.
  int settle_substeps = 0;
  // m/s: a joint whose blocks slip past each other faster than this at a point is left out of
  // the group (its impulses stay as the sweeps left them) and seeds none. Infinite for an
  // impact's group; a settling group's is kSlipShare times the impact margin
  // (converge_impacts.cpp says why; model revision 2026-12-04.2).
  double slip = std::numeric_limits<double>::infinity();
  // Unit vector along gravity (zero without gravity). A block struck through a joint that
  // carries weight (its normal within 45 deg of `down`) settles as after an impact even when
  // the two sweeps took the blow (converge_impacts.cpp, mark_struck; model revision 2026-11-28.7).
  Vec2 down = Vec2::Zero();
  // A group with a manifold between two moving blocks, one at least this many times the other's
  // mass, solves its friction impulses with its normal ones (solve_group_friction.hpp; model
  // revision 2026-12-05.4); 0: never. advance_step.cpp gives converge_heavy's ratio.
  double heavy_mass_ratio = 0.0;
};

struct ImpactCounts {
  long solved = 0;     // groups solved directly
  long too_large = 0;  // groups past max_points: settling ones left to the sweeps, impacts in pieces
  long pieces = 0;     // solves of the pieces of those groups
  long refused = 0;    // solves undone: they would have raised the group's kinetic energy
  long with_friction = 0;  // of `solved` (pieces' solves too), those that solved friction with the normals
};

// Solves the impact groups of this substep in place (velocities and impulses of `state`).
ImpactCounts converge_impacts(std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                              const ImpactConvergence& settings, SweepState& state);

}  // namespace ddafit
