// Exponential slip weakening: the excess of the peak over the residual coefficient decays
// with slip over the same d_c as the bilinear law (the decay with slip that follows a
// velocity step under Ruina's 1983 slip law, here from the peak to the residual),
//   tan(phi(d)) = tan(phi_r) + (tan(phi_p) - tan(phi_r)) exp(-d / d_c),   phi_r = phi_p - i.
// It loses 63 % of the roughness by d_c where the bilinear law loses all of it, and has
// lost 95 % by 3 d_c.
#pragma once

#include <cmath>

#include "forward/contact/laws/friction_state.hpp"

namespace ddafit::laws {

// exp(-d/d_c) below which the law is treated as at its residual (1e-12 of the roughness).
inline constexpr double kExponentialSettledSlip = 27.6;  // d / d_c = ln(1e12)

inline double exponential(const Interface& face, const FrictionState& state) {
  const double mu_p = peak_coefficient(face), mu_r = residual_coefficient(face);
  const double d_c = state.critical_distance;
  const double remaining = d_c > 0.0 ? std::exp(-state.slip / d_c) : 0.0;
  return mu_r + (mu_p - mu_r) * remaining;
}

inline bool exponential_settled(const Interface& face, const FrictionState& state) {
  return face.roughness_angle == 0.0 || state.slip >= kExponentialSettledSlip * state.critical_distance;
}

}  // namespace ddafit::laws
