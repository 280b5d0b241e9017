// Ceres: Levenberg-Marquardt in a trust region with bounds, on residuals (sim - obs)/sigma.
// The Jacobian is taken by our own finite differences with a step of one resolution:
// Ceres' numeric differentiation steps 1e-6 relative, which on an adaptive-step simulation
// measures the time-step controller's noise rather than the physics.
#include <ceres/ceres.h>

#include <cmath>
#include <exception>

#include "inverse/fit.hpp"
#include "inverse/resolution_cost.hpp"

namespace ddafit::inverse {

ResolutionCost::ResolutionCost(Objective& objective, const Scaling& scaling, std::vector<double> values,
                               size_t observations, int budget)
    : objective_(objective), scaling_(scaling), values_(std::move(values)), budget_(budget) {
  set_num_residuals(static_cast<int>(observations));
  mutable_parameter_block_sizes()->push_back(static_cast<int>(scaling.size()));
}

ResolutionCost::Outcome ResolutionCost::residuals_at(const double* u, std::vector<double>& r) const {
  if (budget_ > 0 && calls_ >= budget_) return Outcome::Refused;  // Ceres takes it as a failed step
  ++calls_;
  try {
    scaling_.to_values(u, values_);
    const Evaluation e = objective_.evaluate(values_);
    r = e.residuals;  // a failed run is a large value, not a refusal
    return e.failed ? Outcome::FailedRun : Outcome::Value;
  } catch (...) {
    if (!error_) error_ = std::current_exception();
    return Outcome::Refused;
  }
}

bool ResolutionCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const size_t n = scaling_.size(), m = static_cast<size_t>(num_residuals());
  std::vector<double> r0;
  const Outcome centre = residuals_at(parameters[0], r0);
  if (centre == Outcome::Refused) return false;
  std::copy(r0.begin(), r0.end(), residuals);
  if (!jacobians || !jacobians[0]) return true;
  std::vector<double> u(parameters[0], parameters[0] + n), r;
  for (size_t j = 0; j < n; ++j) {
    // One resolution forward, or backward at the upper bound; a failed neighbour leaves
    // the column zero (the direction then looks flat, and the trust region stays put).
    const double h = u[j] + 1.0 <= scaling_.upper_u[j] ? 1.0 : -1.0;
    u[j] += h;
    const Outcome side = residuals_at(u.data(), r);
    u[j] = parameters[0][j];
    if (error_) return false;
    const bool usable = centre == Outcome::Value && side == Outcome::Value && r.size() == m;
    for (size_t i = 0; i < m; ++i) jacobians[0][i * n + j] = usable ? (r[i] - r0[i]) / h : 0.0;
  }
  return true;
}

namespace {

// Stops on the study's rules (absolute, in resolutions and chi^2) and on the budget;
// Ceres' own tolerances are relative and would stop early or late depending on the offset.
class StudyRules : public ceres::IterationCallback {
 public:
  StudyRules(const ResolutionCost& cost, const MethodOptions& method, int budget)
      : cost_(cost), method_(method), budget_(budget) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    if (cost_.calls() >= budget_) return stop("budget used", false);
    if (it.iteration == 0) return ceres::SOLVER_CONTINUE;
    if (it.step_norm < method_.step_tolerance) return stop("step below step_tolerance x resolution", true);
    if (it.step_is_successful && 2.0 * std::abs(it.cost_change) < method_.chi2_tolerance)
      return stop("chi2 change below chi2_tolerance", true);
    return ceres::SOLVER_CONTINUE;
  }
  std::string reason;
  bool converged = false;

 private:
  ceres::CallbackReturnType stop(const char* why, bool ok) {
    reason = why;
    converged = ok;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  const ResolutionCost& cost_;
  const MethodOptions& method_;
  int budget_;
};

}  // namespace

FitResult fit_ceres(Objective& objective, const Study& study, const std::vector<double>& values,
                    const std::vector<bool>& free, int budget) {
  const Scaling s(study, free);
  objective.reset_best();
  FitResult out;
  std::vector<double> u = s.to_scaled(values);
  if (s.size() == 0) {
    objective.evaluate(values);
  } else {
    auto* cost = new ResolutionCost(objective, s, values, study.observations.size(), budget);
    ceres::Problem problem;  // owns cost
    problem.AddResidualBlock(cost, nullptr, u.data());
    for (size_t k = 0; k < s.size(); ++k) {
      problem.SetParameterLowerBound(u.data(), static_cast<int>(k), 0.0);
      problem.SetParameterUpperBound(u.data(), static_cast<int>(k), s.upper_u[k]);
    }
    StudyRules rules(*cost, study.method, budget);
    ceres::Solver::Options options;
    options.minimizer_type = ceres::TRUST_REGION;
    options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = budget;  // the callback stops on the forward-run budget first
    options.function_tolerance = 0.0;     // the study's rules decide (StudyRules)
    options.parameter_tolerance = 0.0;
    options.gradient_tolerance = 0.0;
    options.logging_type = ceres::SILENT;
    options.callbacks.push_back(&rules);
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (cost->error()) std::rethrow_exception(cost->error());
    out.evaluations = cost->calls();
    out.converged = !rules.reason.empty() ? rules.converged : summary.IsSolutionUsable();
    out.stop_reason = !rules.reason.empty() ? rules.reason : summary.message;
  }
  if (objective.has_best()) {
    out.best = objective.best().values;
    out.chi2 = objective.best().chi2;
  }
  return out;
}

}  // namespace ddafit::inverse
