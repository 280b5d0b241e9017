// Part of an impact group's direct solve (solve_impact_group.cpp): the group's friction impulses
// solved together with its normal impulses, for a group in which a block meets one much lighter
// (ImpactConvergence::heavy_mass_ratio). Elsewhere the group's normal solve holds the friction
// impulses under their new caps and one sweep settles them; across a light block that sweep hands
// the heavy block about m_light / m_heavy of the friction it needs (the Gauss-Seidel ratio of
// converge_heavy.hpp), so a heavy block landing on a row of light cubes on a slope kept sliding
// at the tangential speed it landed with (0.6 m/s at 1000 times a cube, 20 deg) and dragged the
// cubes up to 0.14 m (tests/test_substep_scenes.cpp, SubstepScenesHeavy; model revision
// 2026-12-05.4, docs/theory.md §13c).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

// A share added to the Delassus matrix's diagonal (both of the group's solves): two points on
// one face and a block touching on several faces make the matrix singular, and the term picks
// the least-norm split. At 1e-6 the floor's two points under a row took opposite impulses of
// 1e4 N s/m (a couple the rounding asked for) and the normal solve's active set cycled; 1e-3
// and 1e-2 soften the contacts enough to leave 15 % and 21 % rebounds
// (tests/test_impact_rebound.cpp); 1e-4 holds them.
inline constexpr double kDelassusRegularisation = 1e-4;

// A contact point of a group: manifold and point index.
struct GroupPoint {
  int manifold, point;
};

// The group's points at the start of the solve (the velocities of st), per point i:
// r0[i] its complementarity residual (impact_residual), lambda0[i] and tangent0[i] its
// impulses, floor[i] the least normal impulse (minus a bond's tension); dn0 the normal solve's
// changes of the normal impulses. On success `dn` and `dt` are the changes of the normal and
// friction impulses: a point either stays at its floor and opens, or closes no faster than
// `closing`; its friction either holds the blocks together (tangential velocity within
// `closing`) or sits at its Coulomb cap mu N + c (contact_law.hpp, coulomb_cap) against the slip.
// Returns false when the active set does not settle (the caller keeps its normal solve).
bool solve_friction_with_normals(const std::vector<ContactManifold>& manifolds, const std::vector<GroupPoint>& points,
                                 const std::vector<int>& blocks, const SweepState& st, const Eigen::VectorXd& r0,
                                 const Eigen::VectorXd& lambda0, const Eigen::VectorXd& tangent0,
                                 const Eigen::VectorXd& floor, double closing, const Eigen::VectorXd& dn0,
                                 Eigen::VectorXd& dn, Eigen::VectorXd& dt);

}  // namespace ddafit
