// NLopt through its C interface: the C++ wrapper of 2.7 throws on every non-success code
// (roundoff_limited included) and has no functor objectives.
#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

#include "inverse/fit.hpp"

namespace ddafit::inverse {

Scaling::Scaling(const Study& study, const std::vector<bool>& free) {
  for (size_t j = 0; j < study.parameters.size(); ++j) {
    const Parameter& p = study.parameters[j];
    if (!free[j] || p.discrete()) continue;
    index.push_back(static_cast<int>(j));
    lower.push_back(p.lower);
    resolution.push_back(p.resolution);
    upper_u.push_back((p.upper - p.lower) / p.resolution);
  }
}

void Scaling::to_values(const double* u, std::vector<double>& values) const {
  for (size_t k = 0; k < size(); ++k)
    values[index[k]] = lower[k] + std::clamp(u[k], 0.0, upper_u[k]) * resolution[k];
}

std::vector<double> Scaling::to_scaled(const std::vector<double>& values) const {
  std::vector<double> u(size());
  for (size_t k = 0; k < size(); ++k) u[k] = std::clamp((values[index[k]] - lower[k]) / resolution[k], 0.0, upper_u[k]);
  return u;
}

FitResult fit(Objective& objective, const Study& study, const std::vector<double>& values,
              const std::vector<bool>& free, int budget) {
  return study.method.optimizer == Optimizer::Ceres ? fit_ceres(objective, study, values, free, budget)
                                                    : fit_nlopt(objective, study, values, free, budget);
}

namespace {

struct NloptContext {
  Objective* objective;
  const Scaling* scaling;
  std::vector<double> values;
  nlopt_opt opt = nullptr;
  std::exception_ptr error;  // rethrown once NLopt has returned
  int calls = 0;
};

// The callback NLopt calls. Objective::evaluate reports failures as values; anything else
// thrown here (the cache disk full) must not unwind through C: stop NLopt and say why.
double nlopt_misfit(unsigned, const double* u, double*, void* data) {
  auto* c = static_cast<NloptContext*>(data);
  ++c->calls;
  try {
    c->scaling->to_values(u, c->values);
    return c->objective->evaluate(c->values).chi2;
  } catch (...) {
    c->error = std::current_exception();
    nlopt_force_stop(c->opt);
  }
  return HUGE_VAL;
}

nlopt_algorithm algorithm(const std::string& name) {
  if (name == "LN_SBPLX") return NLOPT_LN_SBPLX;
  if (name == "GN_DIRECT_L") return NLOPT_GN_DIRECT_L;
  return NLOPT_LN_BOBYQA;
}

std::string reason(nlopt_result r) {
  switch (r) {
    case NLOPT_STOPVAL_REACHED: return "stopval reached";
    case NLOPT_FTOL_REACHED: return "chi2 change below chi2_tolerance";
    case NLOPT_XTOL_REACHED: return "step below step_tolerance x resolution";
    case NLOPT_MAXEVAL_REACHED: return "budget used";
    case NLOPT_ROUNDOFF_LIMITED: return "roundoff limited (counted as converged)";
    case NLOPT_FORCED_STOP: return "forced stop";
    case NLOPT_SUCCESS: return "success";
    default: return std::string("NLopt error ") + nlopt_result_to_string(r);
  }
}

}  // namespace

FitResult fit_nlopt(Objective& objective, const Study& study, const std::vector<double>& values,
                    const std::vector<bool>& free, int budget) {
  const Scaling s(study, free);
  objective.reset_best();
  FitResult out;
  const unsigned n = static_cast<unsigned>(s.size());
  std::unique_ptr<nlopt_opt_s, decltype(&nlopt_destroy)> opt(nlopt_create(algorithm(study.method.algorithm), n),
                                                             &nlopt_destroy);
  NloptContext context{&objective, &s, values, opt.get(), nullptr, 0};
  std::vector<double> u = s.to_scaled(values), lo(n, 0.0), hi = s.upper_u, step(n), xtol(n);
  for (unsigned k = 0; k < n; ++k) {
    // First trust radius: a tenth of the range, but at least two resolutions and inside
    // the bounds BOBYQA requires (half the width).
    step[k] = std::min(std::max(0.1 * hi[k], 2.0), 0.5 * hi[k]);
    xtol[k] = study.method.step_tolerance;
  }
  nlopt_set_lower_bounds(opt.get(), lo.data());
  nlopt_set_upper_bounds(opt.get(), hi.data());
  nlopt_set_min_objective(opt.get(), nlopt_misfit, &context);
  nlopt_set_maxeval(opt.get(), budget);
  nlopt_set_xtol_abs(opt.get(), xtol.data());
  nlopt_set_ftol_abs(opt.get(), study.method.chi2_tolerance);
  nlopt_set_initial_step(opt.get(), step.data());
  double f = 0.0;
  const nlopt_result r = n > 0 ? nlopt_optimize(opt.get(), u.data(), &f) : NLOPT_SUCCESS;
  if (n == 0) objective.evaluate(values);
  if (context.error) std::rethrow_exception(context.error);
  out.converged = r == NLOPT_FTOL_REACHED || r == NLOPT_XTOL_REACHED || r == NLOPT_ROUNDOFF_LIMITED ||
                  r == NLOPT_SUCCESS || r == NLOPT_STOPVAL_REACHED;
  out.stop_reason = reason(r);
  out.evaluations = context.calls;
  if (objective.has_best()) {
    out.best = objective.best().values;
    out.chi2 = objective.best().chi2;
  }
  return out;
}

}  // namespace ddafit::inverse
