// Bilinear roughness degradation (Ibanez & Hatzor, seed Eq. 2-3), the default law: the
// roughness part i of the peak angle phi_p is lost linearly over the critical distance d_c
// of accumulated slip d,
//   phi(d) = phi_p - i min(d / d_c, 1),
// so beyond d_c the residual (basic) angle phi_r = phi_p - i governs.
#pragma once

#include <algorithm>

#include "forward/contact/laws/friction_state.hpp"

namespace ddafit::laws {

// tan(phi(d)).
inline double bilinear(const Interface& face, const FrictionState& state) {
  const double d_c = state.critical_distance;
  const double progress = d_c > 0.0 ? std::min(state.slip / d_c, 1.0) : 1.0;
  return tan_degrees(face.friction_angle - face.roughness_angle * progress);
}

// Once d >= d_c (or without roughness) no further slip changes phi.
inline bool bilinear_settled(const Interface& face, const FrictionState& state) {
  return face.roughness_angle == 0.0 || state.slip >= state.critical_distance;
}

}  // namespace ddafit::laws
