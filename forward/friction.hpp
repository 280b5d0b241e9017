// Friction of a sliding contact with the bilinear roughness degradation of the seed
// paper (Ibanez & Hatzor, Eq. 2-3): the roughness part i of the peak angle phi_p is lost
// linearly over the critical distance d_c of accumulated slip d,
//   phi = phi_p - i * min(d / d_c, 1),
// so beyond d_c the residual (basic) angle phi_b = phi_p - i governs.
#pragma once

#include <algorithm>
#include <cmath>

#include "forward/scene.hpp"

namespace ddafit {

// Degraded friction angle in degrees.
inline double degraded_friction_angle(const Interface& face, double slip, double critical_distance) {
  const double progress = critical_distance > 0.0 ? std::min(slip / critical_distance, 1.0) : 1.0;
  return face.friction_angle - face.roughness_angle * progress;
}

inline double tan_degrees(double angle) { return std::tan(angle * M_PI / 180.0); }

}  // namespace ddafit
