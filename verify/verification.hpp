// The built-in analytic suite run by `ddafit verify` and asserted by the tests.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "forward/options.hpp"

namespace ddafit::verification {

struct CheckRow {
  std::string case_name;
  std::string quantity;
  double analytic = 0.0;
  double computed = 0.0;
  double error = 0.0;      // relative unless the quantity says absolute
  double tolerance = 0.0;  // error <= tolerance passes
  bool pass = false;
  std::string why;         // where the tolerance comes from
  // A one-sided check (a bound, not an analytic value): shown in place of `analytic`,
  // e.g. "<= 0.001"; empty for a comparison with an analytic value.
  std::string bound;
};

// Each check runs its scene and returns its rows. Checks are independent.
struct Check {
  std::string name;
  std::function<std::vector<CheckRow>()> run;
};

// The suite run by one solver (the implicit one by default). Names carry "/substep" for
// the substep solver, so both suites can be listed side by side.
std::vector<Check> all_checks(Integrator integrator = Integrator::Implicit);

// One cell of the incline stability map (docs/verification.md): the seed's incline with
// i = 5 deg run at a time step and a penalty, against the integrated Eq. 5.
struct StabilityPoint {
  double penalty_factor = 0.0;  // penalty = factor x Young's modulus
  double time_step = 0.0;       // s
  double omega = 0.0;           // dt sqrt(penalty / block mass)
  double displacement_error = 0.0;  // max relative, where d >= 1 cm
  double acceleration_error = 0.0;  // max relative, central differences over 0.01 s
  bool warned = false;              // the run carried the short-time-step warning
};
std::vector<StabilityPoint> incline_stability_map(const std::vector<double>& penalty_factors,
                                                  const std::vector<double>& time_steps,
                                                  Integrator integrator = Integrator::Implicit);

// One cell of the substep solver's stability map: a scene run at a time step and a
// substep count. The substep solver has no penalty; its settings are these two.
struct SubstepStabilityPoint {
  std::string scene;       // "incline" (seed Eq. 5, phi 25, i 5) or "stack" (five blocks at rest)
  double time_step = 0.0;  // s
  int substeps = 0;
  bool completed = false;
  // incline: worst relative displacement error (d >= 1 cm); stack: top block movement, m.
  double error = 0.0;
  std::string diagnosis;   // the run's message when it did not complete
};
std::vector<SubstepStabilityPoint> substep_stability_map(const std::vector<double>& time_steps,
                                                         const std::vector<int>& substeps);

}  // namespace ddafit::verification
