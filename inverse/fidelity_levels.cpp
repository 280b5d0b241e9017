// method.levels: multi_fidelity, the steps (the correction itself is multi_fidelity.hpp).
// The fine level is the expensive one, so its runs are few and placed where they tell most:
// first across the coarse profile's Delta chi^2 <= 4 range (the correction's slope), then one
// at the corrected model's optimum (its check).
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "inverse/inversion.hpp"
#include "inverse/multi_fidelity.hpp"

namespace ddafit::inverse {

namespace {

// A value of parameter q on its resolution grid, inside its bounds.
double on_grid(const Parameter& q, double v) {
  const double steps = std::round((std::clamp(v, q.lower, q.upper) - q.lower) / q.resolution);
  return std::min(q.upper, q.lower + steps * q.resolution);
}

// The fine runs at `values` of the profiled parameter (the others at the coarse best), with
// the coarse runs at the same points first: the coarse ones are cheap, and the objective's
// best is reset before the fine batch so each fine run that improves on the ones before it
// keeps its history in the cache (the report draws the best fine run's curve from it).
void run_pairs(Objective& objective, const std::vector<double>& coarse_best, const std::vector<double>& values,
               FidelityCorrection& c) {
  std::vector<std::vector<double>> coarse, fine;
  for (double v : values) {
    coarse.push_back(coarse_best);
    coarse.back()[c.parameter] = v;
    fine.push_back(coarse.back());
    fine.back()[c.level_parameter] = c.fine_level;
  }
  const std::vector<Evaluation> a = objective.evaluate_batch(coarse, objective.jobs);
  objective.reset_best();
  const std::vector<Evaluation> b = objective.evaluate_batch(fine, objective.jobs);
  for (size_t i = 0; i < values.size(); ++i) c.runs.push_back({values[i], b[i], a[i], {}});
}

// A start for the corrected model's optimum: the profile's lowest point, moved to the vertex
// of the parabola through it and its neighbours when that lies between them. (The profile's
// own "best" is the coarse fit's point, which is not the corrected model's.)
double parabola_start(const BoundingFriction& f, double fallback) {
  std::vector<const ProfilePoint*> good;
  for (const ProfilePoint& q : f.profile)
    if (!q.failed) good.push_back(&q);
  if (good.empty()) return fallback;
  size_t m = 0;
  for (size_t k = 1; k < good.size(); ++k)
    if (good[k]->chi2 < good[m]->chi2) m = k;
  double at = good[m]->value;
  if (m > 0 && m + 1 < good.size()) {
    const double x0 = good[m - 1]->value, x1 = at, x2 = good[m + 1]->value;
    const double y0 = good[m - 1]->chi2, y1 = good[m]->chi2, y2 = good[m + 1]->chi2;
    const double den = (x0 - x1) * (y0 - y2) - (x0 - x2) * (y0 - y1);
    if (den != 0.0) {
      const double vertex =
          x0 - 0.5 * ((x0 - x1) * (x0 - x1) * (y0 - y2) - (x0 - x2) * (x0 - x2) * (y0 - y1)) / den;
      if (vertex > x0 && vertex < x2) at = vertex;
    }
  }
  return at;
}

// From `start`, steps of one resolution downhill on the corrected model to a minimum on the
// resolution grid (each step a coarse run: the cheap level).
double walk_down(double start, const Parameter& p, const std::vector<double>& best, int profiled,
                 const ProfileScore& score) {
  const auto chi2_at = [&](double v) {
    std::vector<double> x = best;
    x[profiled] = v;
    return score(x).chi2;
  };
  double at = on_grid(p, start);
  double here = chi2_at(at);
  for (int step = 0; step < 1000; ++step) {
    const double down = on_grid(p, at - p.resolution), up = on_grid(p, at + p.resolution);
    const double c_down = down < at ? chi2_at(down) : INFINITY, c_up = up > at ? chi2_at(up) : INFINITY;
    if (here <= c_down && here <= c_up) break;
    at = c_down < c_up ? down : up;
    here = std::min(c_down, c_up);
  }
  return at;
}

// Two values of the profiled parameter name the same grid point.
bool same_point(double a, double b, double resolution) { return std::abs(a - b) < 0.5 * resolution; }

bool has_run(const FidelityCorrection& c, double v, double resolution) {
  return std::any_of(c.runs.begin(), c.runs.end(),
                     [&](const FidelityRun& r) { return same_point(r.value, v, resolution); });
}

}  // namespace

void run_multi_fidelity(Objective& objective, const Study& study, int profiled, int scan, InversionSummary& out) {
  FidelityCorrection& c = out.fidelity;
  c.used = true;
  c.parameter = profiled;
  for (size_t j = 0; j < study.parameters.size(); ++j)
    if (study.parameters[j].discrete()) c.level_parameter = static_cast<int>(j);
  const Parameter& p = study.parameters[profiled];
  const Parameter& level = study.parameters[c.level_parameter];
  c.coarse_level = level.levels.front();
  c.fine_level = level.levels.back();
  const LevelFit& coarse = out.levels.front();
  const std::vector<double> best = coarse.best.values;
  // The objective's log keeps the study's notes (run_inversion sets it); else keep them here.
  const auto log = [&](const std::string& line) {
    if (objective.on_log) objective.on_log(line);
    else out.notes.push_back(line);
  };

  // 1. The coarse profile: where the coarse model puts the answer.
  const BoundingFriction plain = profile_friction(objective, study, best, profiled, scan, false, 1);
  double lo = on_grid(p, plain.delta4.low), hi = on_grid(p, plain.delta4.high);
  if (hi - lo < 4 * p.resolution) {  // a range too narrow to measure a slope across
    lo = on_grid(p, plain.best_value - 2 * p.resolution);
    hi = on_grid(p, plain.best_value + 2 * p.resolution);
  }
  // 2. fine_runs - 1 fine runs spread evenly over it.
  std::vector<double> spread;
  const int n = study.method.fine_runs - 1;
  for (int i = 0; i < n; ++i) {
    const double v = on_grid(p, n == 1 ? plain.best_value : lo + (hi - lo) * i / (n - 1));
    if (std::none_of(spread.begin(), spread.end(), [&](double s) { return same_point(s, v, p.resolution); }))
      spread.push_back(v);
  }
  log(fmt::format("multi_fidelity: coarse fit's best {} = {:.4g}, coarse Delta chi2 <= 4 in [{:.4g}, {:.4g}]; fine runs at "
                  "{}",
                  p.name, plain.best_value, plain.delta4.low, plain.delta4.high, fmt::join(spread, ", ")));
  run_pairs(objective, best, spread, c);
  fit_correction(study, c);

  // 3. The corrected model's optimum (from its profile), one fine run there (the check), the
  // optimum again with that run in the correction, and the profile centred on it (its "best").
  const ProfileScore score = [&](const std::vector<double>& x) { return corrected(study, c, objective.evaluate(x)); };
  std::vector<double> centre = best;
  BoundingFriction f = profile_friction(objective, study, centre, profiled, scan, false, 1, score);
  centre[profiled] = walk_down(parabola_start(f, best[profiled]), p, best, profiled, score);
  if (!has_run(c, centre[profiled], p.resolution)) {
    c.check_predicted_chi2 = score(centre).chi2;
    run_pairs(objective, best, {centre[profiled]}, c);
    c.check_chi2 = c.runs.back().fine.chi2;
    c.checked = !c.runs.back().fine.failed;
    log(fmt::format("multi_fidelity: check run at {} = {:.4g}: chi2 {:.4g} against {:.4g} predicted", p.name,
                    centre[profiled], c.check_chi2, c.check_predicted_chi2));
    fit_correction(study, c);
    centre[profiled] = walk_down(centre[profiled], p, best, profiled, score);
  }
  f = profile_friction(objective, study, centre, profiled, scan, false, 1, score);
  f.corrected = true;
  log(fmt::format("multi_fidelity: {} fine runs; the fine runs' misfit against the corrected model, RMS {:.3g} sigma",
                  c.runs.size(), c.rms_sigma));

  // The fine level as a level of the report: its best run, its runs as its evaluations.
  LevelFit fine;
  fine.start = best;
  fine.start[c.level_parameter] = c.fine_level;
  const FidelityRun* top = nullptr;
  for (const FidelityRun& r : c.runs)
    if (!r.fine.failed && (!top || r.fine.chi2 < top->fine.chi2)) top = &r;
  fine.best = top ? top->fine : c.runs.back().fine;
  fine.fit.evaluations = static_cast<int>(c.runs.size());
  fine.fit.best = fine.best.values;
  fine.fit.chi2 = fine.best.chi2;
  fine.fit.converged = top != nullptr;
  fine.fit.stop_reason = fmt::format("multi_fidelity: {} runs correct the coarse model", c.runs.size());
  out.levels.push_back(std::move(fine));
  out.best_level = 1;
  if (!top) {
    f.available = false;
    f.why_not = "every run of the fine level failed, so the coarse model could not be corrected";
  }
  out.friction = std::move(f);
}

}  // namespace ddafit::inverse
