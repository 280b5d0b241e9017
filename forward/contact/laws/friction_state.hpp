// What a friction law reads from a sliding face (forward/contact/friction_law.hpp): its slip
// history and its slip speed, and the interface's angles.
#pragma once

#include <cmath>

#include "forward/scene.hpp"

namespace ddafit {

inline double tan_degrees(double angle) { return std::tan(angle * M_PI / 180.0); }

namespace laws {

struct FrictionState {
  double slip = 0.0;               // d: accumulated while the face touches, m (seed Eq. 2)
  double slip_rate = 0.0;          // |v|: the face's slip speed, m/s
  double critical_distance = 0.0;  // d_c: critical_distance_ratio x the overriding block's length, m
  double normal_stress = 0.0;      // sigma_n', the face's effective normal stress last (sub)step, Pa
  double excess_pressure = 0.0;    // Delta p, the shear band's pore pressure above ambient, Pa
};

// mu_p = tan(phi_p) and mu_r = tan(phi_p - i): the peak and residual coefficients.
inline double peak_coefficient(const Interface& face) { return tan_degrees(face.friction_angle); }
inline double residual_coefficient(const Interface& face) {
  return tan_degrees(face.friction_angle - face.roughness_angle);
}

}  // namespace laws
}  // namespace ddafit
