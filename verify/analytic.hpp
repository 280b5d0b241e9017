// Closed-form and quadrature solutions the verification cases compare against.
#pragma once

#include <vector>

namespace ddafit::verification {

// Block on an incline with the bilinear degradation law (seed Eq. 4-5): acceleration
// a(d) = g (sin alpha - cos alpha tan(phi_p - i min(d/d_c, 1))).
struct InclineAnalytic {
  double gravity = 9.81;
  double slope_angle = 0.0;     // alpha, deg
  double friction_angle = 0.0;  // phi_p, deg
  double roughness_angle = 0.0; // i, deg
  double critical_distance = 0.0;  // d_c, m

  double acceleration(double d) const;
  // Downslope distance and speed at the given times, starting from rest: Eq. 4 when
  // i = 0, otherwise d'' = a(d) integrated by RK4 with 1e-5 s steps (error < 1e-12 m).
  void solve(const std::vector<double>& times, std::vector<double>& distance, std::vector<double>& speed) const;
};

}  // namespace ddafit::verification
