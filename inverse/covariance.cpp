// The linearised covariance (J^T J)^-1 of the weighted residuals at the best point, by
// ceres::Covariance on the same resolution-step Jacobian the Ceres fit uses. A secondary
// diagnostic: it ignores bounds and assumes linearity, so it comes with warnings saying
// when it cannot be read as an uncertainty.
#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <cmath>

#include "inverse/inversion.hpp"
#include "inverse/resolution_cost.hpp"

namespace ddafit::inverse {

CovarianceReport covariance_at(Objective& objective, const Study& study, const std::vector<double>& best,
                               int profiled) {
  CovarianceReport c;
  std::vector<bool> free;
  for (const Parameter& p : study.parameters) free.push_back(!p.discrete());
  const Scaling s(study, free);
  const size_t n = s.size();
  c.parameters = s.index;
  long values_observed = 0;
  for (const Observation& o : study.observations) values_observed += o.kind == ObservationKind::Equal;
  if (values_observed <= static_cast<long>(n))
    c.warnings.push_back(std::to_string(values_observed) + " value observations for " + std::to_string(n) +
                         " parameters: no degrees of freedom left, so the covariance is not an uncertainty; "
                         "use the profile");
  for (size_t k = 0; k < n; ++k) {
    const Parameter& p = study.parameters[s.index[k]];
    const double x = best[s.index[k]];
    if (x - p.lower < p.resolution || p.upper - x < p.resolution)
      c.warnings.push_back(p.name + " = " + exact_text(x) + " is within one resolution of a bound; the covariance "
                           "ignores the bound");
  }

  std::vector<double> u = s.to_scaled(best);
  auto* cost = new ResolutionCost(objective, s, best, study.observations.size(), 0);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, u.data());
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), nullptr, nullptr, nullptr, &crs);
  if (cost->error()) std::rethrow_exception(cost->error());
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; r < crs.num_rows; ++r)
    for (int i = crs.rows[r]; i < crs.rows[r + 1]; ++i) jac(r, crs.cols[i]) = crs.values[i];
  for (size_t k = 0; k < n; ++k)
    if (jac.col(static_cast<Eigen::Index>(k)).norm() == 0.0)
      c.warnings.push_back(study.parameters[s.index[k]].name +
                           " changes no residual by one resolution step here: the data do not constrain it");
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(jac).singularValues();
  // Fewer rows than columns: J has fewer singular values than parameters, rank < n.
  const bool square_enough = jac.rows() >= jac.cols() && sv.size() > 0;
  c.condition_number = square_enough && sv(sv.size() - 1) > 0.0 ? sv(0) / sv(sv.size() - 1) : INFINITY;
  // ceres::Covariance drops exactly-zero eigenvalues silently (a pseudo-inverse), so rank
  // deficiency is judged here, on the same test Ceres applies to the non-zero ones.
  if (!(c.condition_number < 1e6)) {
    c.warnings.push_back("the weighted Jacobian is rank deficient (condition number " +
                         exact_text(c.condition_number) + "): no covariance; the data do not resolve every parameter");
    return c;
  }
  if (c.condition_number > 1e3)
    c.warnings.push_back("the weighted Jacobian is ill-conditioned (condition number " +
                         exact_text(c.condition_number) + "): some combination of parameters is poorly resolved");

  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;  // reports rank deficiency instead of failing obscurely
  options.null_space_rank = 0;
  options.min_reciprocal_condition_number = 1e-12;  // = (1e6 condition of J)^-2, as above
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> blocks{{u.data(), u.data()}};
  if (!covariance.Compute(blocks, &problem)) {
    c.warnings.push_back("ceres::Covariance could not invert J^T J (rank deficient): no covariance");
    return c;
  }
  if (cost->error()) std::rethrow_exception(cost->error());
  std::vector<double> cov_u(n * n);
  covariance.GetCovarianceBlock(u.data(), u.data(), cov_u.data());
  c.computed = true;
  c.matrix.assign(n, std::vector<double>(n));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) c.matrix[i][j] = cov_u[i * n + j] * s.resolution[i] * s.resolution[j];
  for (size_t i = 0; i < n; ++i) c.standard_deviation.push_back(std::sqrt(std::max(0.0, c.matrix[i][i])));
  for (size_t k = 0; k < n; ++k) {
    if (s.index[k] != profiled) continue;
    // Delta method on mu_b(p), with the derivative over one resolution (the same step).
    const double p = best[profiled], h = s.resolution[k];
    const double phi = objective.scene().peak_friction_angle(best, study.parameters[profiled].key);
    const double slope = (residual_friction(study, profiled, phi, p + h) - residual_friction(study, profiled, phi, p)) / h;
    c.mu_standard_deviation = std::abs(slope) * c.standard_deviation[k];
  }
  return c;
}

}  // namespace ddafit::inverse
