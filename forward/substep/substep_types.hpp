// Plain data of the substep solver (docs/theory.md, "The substep solver"): each block's
// effective inverse mass for one substep. The contacts it works on are the shared contact
// stage's (forward/contact/contact_types.hpp): manifolds whose points carry an
// ImpulseState.
#pragma once

#include <cmath>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {

// A block's response to a contact impulse P at r: its velocity changes by P / m and its
// spin by (r x P) / I, with m and I the rigid-body rows of the DDA mass matrix
// (translation and rotation about the centroid; they are diagonal there,
// forward/mass_matrix.hpp). The strain unknowns carry no inertia in the substep solver:
// a block's strain follows from the mean stress its contacts put on it over each step
// (forward/substep/block_stress.hpp). A fixed block has zero inverses.
struct BlockMass {
  double inverse_mass = 0.0;     // 1 / m, m/kg (per metre of thickness)
  double inverse_inertia = 0.0;  // 1 / I about the centroid
  bool moves = false;
};

// The fastest a vertex of block b moves relative to its centroid: the rotation and strain rates
// times the block's reach (its largest vertex distance from the centroid).
inline double turn_speed_bound(const Block& b, double reach) {
  const Vec6& v = b.velocity;
  return reach * (std::abs(v[2]) + std::abs(v[3]) + std::abs(v[4]) + std::abs(v[5]));
}

// The fastest a vertex of block b moves: centroid speed plus turn_speed_bound. The step
// control and sleeping read it.
inline double vertex_speed_bound(const Block& b, double reach) {
  const Vec6& v = b.velocity;
  return std::hypot(v[0], v[1]) + turn_speed_bound(b, reach);
}

}  // namespace ddafit
