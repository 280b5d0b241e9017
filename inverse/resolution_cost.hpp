// A Ceres cost whose Jacobian is a finite difference with a step of one resolution per
// parameter (one unit in the scaled coordinates of fit.hpp). Used by the Ceres fit and by
// the covariance diagnostic, so both see the same derivatives.
#pragma once

#include <ceres/cost_function.h>

#include <exception>
#include <vector>

#include "inverse/fit.hpp"

namespace ddafit::inverse {

class ResolutionCost : public ceres::CostFunction {
 public:
  // budget: objective calls allowed (0 = no limit); past it Evaluate returns false.
  ResolutionCost(Objective& objective, const Scaling& scaling, std::vector<double> values, size_t observations,
                 int budget);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  int calls() const { return calls_; }
  // Anything other than a failed run (e.g. the cache cannot be written): rethrown by the
  // caller after Ceres returns, never through Ceres.
  std::exception_ptr error() const { return error_; }

 private:
  enum class Outcome { Value, FailedRun, Refused };
  Outcome residuals_at(const double* u, std::vector<double>& r) const;
  Objective& objective_;
  const Scaling& scaling_;
  mutable std::vector<double> values_;
  int budget_;
  mutable int calls_ = 0;
  mutable std::exception_ptr error_;
};

}  // namespace ddafit::inverse
