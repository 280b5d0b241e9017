// The contact law both solvers share: Mohr-Coulomb with the bilinear roughness
// degradation of the seed paper (Ibanez & Hatzor, Eq. 2-3), cohesion and tension.
//
//   phi(d) = phi_p - i * min(d / d_c, 1)                (seed Eq. 2-3)
//   |shear| <= N tan(phi(d)) + c l_c     while bonded   (Mohr-Coulomb)
//   N >= -T l_c                          while bonded   (tension cut-off)
//
// d is the slip accumulated at the contact, d_c the critical distance (a fraction of the
// overriding block's length), l_c the length the bond acts on. A bond (cohesion c and
// tensile strength T) exists only between blocks touching at t = 0 and is lost for good
// once the contact slides or opens. The implicit solver applies the law to forces
// (forward/step/check_contacts.cpp), the substep solver to impulses over a substep
// (forward/substep/solve_contacts.cpp); both call the functions below.
#pragma once

#include "forward/friction.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// Friction coefficient tan(phi) at accumulated slip d (seed Eq. 2-3).
inline double friction_coefficient(const Interface& face, double slip, double critical_distance) {
  return tan_degrees(degraded_friction_angle(face, slip, critical_distance));
}

// Largest shear force a contact carries before it slides: N tan(phi(d)) plus, while
// bonded, the cohesion over the bond length.
inline double shear_strength(const Interface& face, double normal_force, double slip, double critical_distance,
                             bool bonded, double bond_length) {
  const double cohesion = bonded ? face.cohesion * bond_length : 0.0;
  return normal_force * friction_coefficient(face, slip, critical_distance) + cohesion;
}

// Largest tensile normal force (>= 0) a contact carries before it opens.
inline double tensile_capacity(const Interface& face, bool bonded, double bond_length) {
  return bonded ? face.tensile_strength * bond_length : 0.0;
}

}  // namespace ddafit
