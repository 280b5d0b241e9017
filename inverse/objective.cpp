#include "inverse/objective.hpp"

#include <chrono>
#include <cmath>
#include <algorithm>
#include <limits>

#include "forward/top_surface.hpp"

namespace ddafit::inverse {

double summary_value(const PointSummary& p, const std::string& quantity) {
  for (const PointQuantity& q : kPointQuantities)
    if (quantity == q.name) return q.get(p);
  return std::numeric_limits<double>::quiet_NaN();
}

double observation_residual(const Observation& o, double simulated, double sigma) {
  const double r = (simulated - o.value) / sigma;
  const bool counts = o.kind == ObservationKind::Equal || (o.kind == ObservationKind::AtMost && r > 0.0) ||
                      (o.kind == ObservationKind::AtLeast && r < 0.0);
  return counts ? r : 0.0;
}

double chi2_observations_only(const Study& study, const Evaluation& e) {
  if (e.failed) return e.chi2;
  double chi2 = 0.0;
  for (size_t k = 0; k < study.observations.size() && k < e.simulated.size(); ++k) {
    const double r = observation_residual(study.observations[k], e.simulated[k], study.observations[k].sigma);
    chi2 += r * r;
  }
  return chi2;
}

Objective::Objective(const Study& study, EvaluationCache& cache, ForwardModel forward)
    : study_(study), scene_(study), cache_(cache), forward_(std::move(forward)) {}

Evaluation Objective::score(const std::vector<double>& values, const SimulationSummary& summary) const {
  Evaluation e;
  e.values = values;
  const size_t m = study_.observations.size();
  e.simulated.assign(m, std::numeric_limits<double>::quiet_NaN());
  e.residuals.assign(m, 0.0);
  e.failed = summary.status != RunStatus::Completed;
  e.message = summary.message;
  for (const PointSummary& p : summary.points) e.point_names.push_back(p.name);
  for (size_t k = 0; k < m && !e.failed; ++k) {
    const Observation& o = study_.observations[k];
    if (o.is_deposit()) {
      e.simulated[k] = surface_misfit_rms(summary.final_surface, o.surface, o.from, o.to);
    } else {
      for (const PointSummary& p : summary.points)
        if (p.name == o.point) e.simulated[k] = summary_value(p, o.quantity);
    }
    if (!std::isfinite(e.simulated[k])) {
      e.failed = true;
      e.message = o.is_deposit() ? "the run left no ground surface over [" + std::to_string(o.from) + ", " +
                                       std::to_string(o.to) + "] m (a cached run from before deposits were kept?)"
                                 : "the run's summary has no finite " + o.quantity + " for point " + o.point;
      break;
    }
    e.residuals[k] = observation_residual(o, e.simulated[k], o.effective_sigma());
    e.chi2 += e.residuals[k] * e.residuals[k];
  }
  if (e.failed) {
    // Rising away from the start (in units of each parameter's range) by at most 1e3 per
    // parameter, so the value stays near kFailedMisfit and far above any real fit.
    double away = 0.0;
    for (size_t j = 0; j < study_.parameters.size(); ++j) {
      const Parameter& p = study_.parameters[j];
      if (p.discrete()) continue;
      const double d = (values[j] - p.start) / (p.upper - p.lower);
      away += 1e3 * d * d;
    }
    e.chi2 = kFailedMisfit + away;
    e.residuals.assign(m, std::sqrt(e.chi2 / static_cast<double>(m)));
  }
  return e;
}

Evaluation Objective::evaluate(const std::vector<double>& values) { return record(values, nullptr, 0.0); }

std::optional<CachedRun> Objective::usable_cached(const std::string& key) const {
  std::optional<CachedRun> hit = cache_.find(key);
  if (!hit || hit->result.summary.status != RunStatus::Completed || !hit->result.summary.final_surface.empty())
    return hit;
  for (const Observation& o : study_.observations)
    if (o.is_deposit()) return std::nullopt;  // run it again: the deposit needs the surface
  return hit;
}

Evaluation Objective::record(const std::vector<double>& values, SimulationResult* made, double made_seconds) {
  const std::string key = point_key(study_, values);
  if (const auto it = seen_.find(key); it != seen_.end()) {
    // Seen in this process (an optimiser revisiting, or another fit): never run twice.
    if (best_ < 0 || log_[it->second].chi2 < log_[best_].chi2) {
      best_ = static_cast<long>(it->second);
      best_history_.clear();  // the report looks for it in the cache
    }
    return log_[it->second];
  }

  Evaluation e;
  std::vector<HistoryRow> history;
  if (std::optional<CachedRun> hit = usable_cached(key)) {
    e = score(values, hit->result.summary);
    e.cached = true;
    e.wall_seconds = hit->wall_seconds;
    ++cached_;
    seconds_cached_ += hit->wall_seconds;
    history = std::move(hit->result.history);
  } else {
    SimulationResult run;
    double seconds = made_seconds;
    if (made) {
      run = std::move(*made);
    } else {
      const auto t0 = std::chrono::steady_clock::now();
      run = scene_.run(values, forward_);
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    ++run_;
    seconds_run_ += seconds;
    e = score(values, run.summary);
    e.wall_seconds = seconds;
    // Histories are kept for new best points only: the report draws the best fit's curve.
    const bool is_best = !e.failed && (best_ < 0 || e.chi2 < log_[best_].chi2);
    cache_.store(key, run, seconds, is_best);
    if (is_best) history = std::move(run.history);
  }
  if (e.failed && on_log)
    on_log("evaluation " + std::to_string(log_.size() + 1) + ": counted as chi2 = " + std::to_string(e.chi2) +
           " because the forward run failed: " + e.message);
  if (e.failed) ++failed_;
  seen_[key] = log_.size();
  log_.push_back(std::move(e));
  best_chi2_ = std::min(best_chi2_, log_.back().chi2);
  if (best_ < 0 || log_.back().chi2 < log_[best_].chi2) {
    best_ = static_cast<long>(log_.size()) - 1;
    best_history_ = std::move(history);
  }
  if (on_progress) on_progress(progress());
  return log_.back();
}

void Objective::reset_best() {
  best_ = -1;
  best_history_.clear();
}

Progress Objective::progress() const {
  Progress p;
  p.evaluations = static_cast<long>(log_.size());
  p.cached = cached_;
  p.failed = failed_;
  p.running = running_;
  p.run = run_;
  p.best_chi2 = best_chi2_;
  p.mean_run_seconds = run_ > 0 ? seconds_run_ / run_ : (cached_ > 0 ? seconds_cached_ / cached_ : 0.0);
  p.planned = planned_;
  // Runs made `jobs` at a time finish that many times sooner.
  p.eta_seconds = std::max(0L, planned_ - p.evaluations) * p.mean_run_seconds / std::max(1, jobs);
  return p;
}

}  // namespace ddafit::inverse
