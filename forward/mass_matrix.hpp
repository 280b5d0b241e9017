// The mass matrix of a DDA block, shared by both solvers.
#pragma once

#include "forward/block_system.hpp"

namespace ddafit {

// Mass matrix of one block divided by density: the integral of T^T T over the block
// (formulation digest, "Inertia"), from the area and second moments about the centroid.
inline Mat6 unit_mass_matrix(const Block& b) {
  const double sxx = b.s_xx, syy = b.s_yy, sxy = b.s_xy;
  Mat6 m = Mat6::Zero();
  m(0, 0) = m(1, 1) = b.area;
  m(2, 2) = sxx + syy;
  m(2, 3) = m(3, 2) = -sxy;
  m(2, 4) = m(4, 2) = sxy;
  m(2, 5) = m(5, 2) = 0.5 * (sxx - syy);
  m(3, 3) = sxx;
  m(3, 5) = m(5, 3) = 0.5 * sxy;
  m(4, 4) = syy;
  m(4, 5) = m(5, 4) = 0.5 * sxy;
  m(5, 5) = 0.25 * (sxx + syy);
  return m;
}

// The rigid velocity (u0', v0', omega) that carries block b's linear and angular momentum:
// (M V)_i / M_ii for i = 0, 1, 2 (M above, V the block's six rates). The translation is the
// centroid's; the rotation is not DDA's r0' once the block strains, since M couples r0 to the
// strain rates (M_23, M_24, M_25: a shear rate gamma' turns a long block's ends as r0' would,
// gamma' (s_xx - s_yy) / 2 of angular momentum). An impulse on the rigid unknowns that meets the
// velocity of this rigid motion at a point changes the kinetic energy 1/2 V^T M V by
// P . (v_before + v_after) / 2 there, so it can only take energy out; met with r0' instead it
// pumped a strain mode of a slab sliding at short steps until the run stopped on "contacts are
// creating energy" (docs/theory.md §7a, "The rigid motion an impulse meets"; until model
// revision 2026-12-06.14, forward/step/resolve_impacts.cpp).
inline Vec3 momentum_rigid_velocity(const Block& b) {
  Vec3 v = b.velocity.head<3>();
  const double turning = b.s_xx + b.s_yy;
  if (turning > 0.0)
    v[2] += (-b.s_xy * b.velocity[3] + b.s_xy * b.velocity[4] + 0.5 * (b.s_xx - b.s_yy) * b.velocity[5]) / turning;
  return v;
}

}  // namespace ddafit
