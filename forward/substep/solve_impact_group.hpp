// The direct solve of an impact group (stage 4b of a substep, converge_impacts.cpp): the
// normal impulses of a group's contact points solved together as one linear complementarity
// problem (Signorini's conditions, by an active set on the Delassus matrix), the friction
// impulses held under their Coulomb caps, and the answer refused when it would add kinetic
// energy (docs/theory.md §13c).
#pragma once

#include <vector>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

// A point's complementarity residual (Signorini: impulse >= its floor, residual >= 0, one of
// them at its bound): its normal velocity less the closing its gap allows within the substep
// (the speculative contact of solve_contacts.cpp).
// Of the blocks' velocities `v` (st.velocity unless given: mark_struck reads the free ones).
double impact_residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h,
                       const std::vector<Vec3>& v);
double impact_residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h);

// How a group's solve ended.
enum class GroupSolve {
  Refused,             // undone: it would have raised the group's kinetic energy
  Normals,             // normal impulses solved together, friction held under the new caps
  NormalsAndFriction,  // friction solved with them (solve_group_friction.hpp)
};

// Solves the normal impulses of the points of manifolds `list` together, to within
// 1 % of `closing` (m/s, the speed that starts a group), then friction and one sweep. The
// friction is solved with the normals when a manifold of the list joins two moving blocks one
// at least `heavy_mass_ratio` times the other (0: never), in groups of up to 64 points. Refused,
// with velocities and impulses unchanged, when the answer would leave the group's blocks more
// kinetic energy than before (beyond 1 % and half its mass times closing^2).
GroupSolve solve_impact_group(std::vector<ContactManifold>& manifolds, const std::vector<int>& list,
                              const SweepSettings& relax, double closing, double heavy_mass_ratio, SweepState& st);

}  // namespace ddafit
