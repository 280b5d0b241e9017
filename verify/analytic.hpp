// Closed-form and quadrature solutions the verification cases compare against.
#pragma once

#include <vector>

#include "forward/run_summary.hpp"

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

// Housner's rocking block (Bull. Seismol. Soc. Am. 53(2), 1963): a rigid b x H block released
// from rest tilted by theta0 about a base corner rocks with its angular velocity multiplied by
// r = 1 - (3/2) sin^2(alpha), alpha = atan(b / H), at each impact (angular momentum kept about
// the new corner; no bounce, no slip); between impacts its energy is kept.
struct HousnerRocking {
  double base = 1.0, height = 1.0;  // b, H (m)
  double gravity = 9.81;

  double alpha() const;         // rad
  double frequency() const;     // p = sqrt(3 g / 4 R), R the half-diagonal, 1/s
  double energy_kept() const;   // r^2, the share of the rocking energy an impact keeps
  // Rocking energy at tilt theta, per m g R: cos(alpha - theta) - cos(alpha).
  double energy(double theta) const;
  // From rest at theta0 to the first impact: arccosh(alpha / (alpha - theta0)) / p (the
  // linearised equation, within 0.5 % of the exact one for theta0 up to 0.6 alpha).
  double first_impact(double theta0) const;
  // From rest at theta0 until the peaks, falling by r^2 in energy, are 1e-7 alpha.
  double time_to_rest(double theta0) const;
};

// A rocking run's tilt, from history rows of two material points (the column's base and top
// centres, in that order at each output): the time the tilt first changes sign, and |tilt| at
// each half-cycle's peak (the release first).
struct RockingTrace {
  double first_impact = -1.0;  // s; -1 if it never changed sign
  std::vector<double> peaks;   // rad
};
RockingTrace rocking_trace(const std::vector<HistoryRow>& history);

}  // namespace ddafit::verification
