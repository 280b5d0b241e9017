// One local (or global) fit of the continuous parameters at fixed levels, by NLopt or
// Ceres. Both work in scaled units, u = (x - lower) / resolution, so that one unit is the
// smallest change that matters in every direction: the trust region, the finite-difference
// step and the stopping rules then mean the same thing for every parameter.
#pragma once

#include <string>
#include <vector>

#include "inverse/objective.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

struct FitResult {
  std::vector<double> best;  // all parameters; the best point the objective saw in this fit
  double chi2 = 0.0;
  int evaluations = 0;       // objective calls in this fit (cached or run)
  bool converged = false;    // a stopping rule fired (not the budget, not an error)
  std::string stop_reason;   // in the optimiser's words
};

// The free parameters' scaled coordinates.
struct Scaling {
  std::vector<int> index;  // study parameter of each free coordinate
  std::vector<double> lower, resolution, upper_u;

  Scaling(const Study& study, const std::vector<bool>& free);
  size_t size() const { return index.size(); }
  // Writes u into a full parameter vector (clamped to the bounds).
  void to_values(const double* u, std::vector<double>& values) const;
  std::vector<double> to_scaled(const std::vector<double>& values) const;
};

// Fits the parameters marked free, starting from `values` (others stay fixed there), with
// at most `budget` objective calls. The objective's best is reset at the start.
FitResult fit(Objective& objective, const Study& study, const std::vector<double>& values,
              const std::vector<bool>& free, int budget);

FitResult fit_nlopt(Objective& objective, const Study& study, const std::vector<double>& values,
                    const std::vector<bool>& free, int budget);
FitResult fit_ceres(Objective& objective, const Study& study, const std::vector<double>& values,
                    const std::vector<bool>& free, int budget);

}  // namespace ddafit::inverse
