// The friction law behind the contact law: tan(phi) of a sliding face from its slip
// history. One law today, the seed's; a law is a function of the interface and the face's
// slip history, and contact_law.hpp is the only caller, so another law plugs in here.
//
// Bilinear roughness degradation (Ibanez & Hatzor, seed Eq. 2-3): the roughness part i of
// the peak angle phi_p is lost linearly over the critical distance d_c of accumulated slip d,
//   phi(d) = phi_p - i min(d / d_c, 1),
// so beyond d_c the residual (basic) angle phi_b = phi_p - i governs.
#pragma once

#include <algorithm>
#include <cmath>

#include "forward/scene.hpp"

namespace ddafit {

inline double tan_degrees(double angle) { return std::tan(angle * M_PI / 180.0); }

// phi(d) of seed Eq. 2-3, degrees.
inline double bilinear_friction_angle(const Interface& face, double slip, double critical_distance) {
  const double progress = critical_distance > 0.0 ? std::min(slip / critical_distance, 1.0) : 1.0;
  return face.friction_angle - face.roughness_angle * progress;
}

// tan(phi) at accumulated slip d.
inline double friction_law(const Interface& face, double slip, double critical_distance) {
  return tan_degrees(bilinear_friction_angle(face, slip, critical_distance));
}

// Whether more slip can change the friction of a face that has slipped d: not once the
// roughness is gone (d >= d_c), nor without roughness. Lets the solvers skip the law for the
// many contacts that have reached their residual friction.
inline bool friction_law_settled(const Interface& face, double slip, double critical_distance) {
  return face.roughness_angle == 0.0 || slip >= critical_distance;
}

}  // namespace ddafit
