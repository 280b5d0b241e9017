#include "inverse/model_spread.hpp"
#include "inverse/scan_design.hpp"

#include <cmath>
#include <filesystem>
#include <set>

#include "inverse/evaluation_cache.hpp"

namespace ddafit::inverse {
namespace {

std::vector<UnitPoint> unit_design(int dims, const DesignOptions& o, MorrisDesign* morris) {
  switch (o.kind) {
    case DesignKind::Grid: return grid_design(dims, o.points);
    case DesignKind::LatinHypercube: return latin_hypercube(dims, o.samples, o.seed);
    case DesignKind::Morris: *morris = morris_design(dims, o.trajectories, o.levels, o.seed); return morris->points;
  }
  return {};
}

// Every combination of the discrete parameters' levels, first parameter slowest.
std::vector<std::vector<double>> level_combinations(const Study& study) {
  std::vector<std::vector<double>> combos{{}};
  for (const Parameter& p : study.parameters) {
    if (!p.discrete()) continue;
    std::vector<std::vector<double>> next;
    for (const auto& c : combos)
      for (double level : p.levels) {
        next.push_back(c);
        next.back().push_back(level);
      }
    combos = std::move(next);
  }
  return combos;
}

// The profiled parameter of the bounding friction (profile_parameter()), its interface
// and peak angle; mu_b over the runs with chi2 <= best + threshold.
FrictionSpread spread(const Study& study, const StudyScene& scene, const DesignResult& r, double threshold) {
  FrictionSpread f;
  const int q = profile_parameter(study);
  if (q < 0) {
    f.why_not = "no parameter of the study sets a degradation percent or roughness angle";
    return f;
  }
  if (r.best < 0) {
    f.why_not = "every run failed";
    return f;
  }
  const Parameter& p = study.parameters[q];
  f.parameter = p.name;
  const std::string rest = p.key.substr(std::string("interfaces.").size());
  f.interface = rest.substr(0, rest.find('.'));
  const double limit = r.runs[r.best].chi2 + threshold;
  f.mu_low = INFINITY;
  f.mu_high = -INFINITY;
  for (const Evaluation& e : r.runs) {
    if (e.failed || e.chi2 > limit) continue;
    const double peak = scene.peak_friction_angle(e.values, p.key);
    if (!std::isfinite(peak)) continue;
    const double mu = residual_friction(study, q, peak, e.values[q]);
    f.mu_low = std::min(f.mu_low, mu);
    f.mu_high = std::max(f.mu_high, mu);
    ++f.runs;
  }
  f.available = f.runs > 0;
  if (!f.available) f.why_not = "no run within the threshold has a friction angle";
  return f;
}

}  // namespace

int continuous_count(const Study& study) {
  int n = 0;
  for (const Parameter& p : study.parameters) n += p.discrete() ? 0 : 1;
  return n;
}

std::vector<std::vector<double>> design_values(const Study& study, const DesignOptions& o) {
  MorrisDesign morris;
  const std::vector<UnitPoint> unit = unit_design(continuous_count(study), o, &morris);
  std::vector<std::vector<double>> out;
  for (const std::vector<double>& combo : level_combinations(study)) {
    for (const UnitPoint& u : unit) {
      std::vector<double> x;
      size_t c = 0, d = 0;
      for (const Parameter& p : study.parameters)
        x.push_back(p.discrete() ? combo[c++] : p.lower + u[d++] * (p.upper - p.lower));
      out.push_back(std::move(x));
    }
  }
  return out;
}

DesignPlan plan_points(const Study& study, const InversionOptions& options, const std::vector<std::vector<double>>& points) {
  DesignPlan plan;
  plan.points = static_cast<long>(points.size());
  std::set<std::string> keys;
  for (const auto& x : points) keys.insert(point_key(study, x));
  plan.distinct = static_cast<long>(keys.size());
  const std::filesystem::path path = std::filesystem::path(options.out_dir) / "evaluations.sqlite";
  if (!std::filesystem::exists(path)) return plan;
  const EvaluationCache cache(path.string(), options.model_version, scene_input_hash(study));
  double seconds = 0.0;
  for (const std::string& key : keys)
    if (const auto hit = cache.find(key)) {
      ++plan.cached;
      seconds += hit->wall_seconds;
    }
  plan.mean_cached_seconds = plan.cached > 0 ? seconds / static_cast<double>(plan.cached) : 0.0;
  return plan;
}

DesignResult run_design(const Study& given, const InversionOptions& options, const DesignOptions& design,
                        const ForwardModel& forward) {
  DesignResult r;
  const std::unique_ptr<EvaluationCache> cache = open_cache(given, options, &r.cache_path);
  // A `model_sigma: ensemble` is measured once, before the design; chi2 then uses sigma_eff.
  const ModelSpread model = measure_model_spread(given, spread_runs(options), *cache, forward);
  for (const std::string& line : model.notes)
    if (options.on_log) options.on_log(line);
  const Study& study = model.study;
  Objective objective(study, *cache, forward);
  apply_options(objective, options);
  const std::vector<std::vector<double>> points = design_values(study, design);
  objective.set_planned(static_cast<long>(points.size()));
  r.runs = objective.evaluate_batch(points, options.jobs);
  for (size_t k = 0; k < r.runs.size(); ++k)
    if (!r.runs[k].failed && (r.best < 0 || r.runs[k].chi2 < r.runs[r.best].chi2)) r.best = static_cast<long>(k);
  r.within1 = spread(study, objective.scene(), r, 1.0);
  r.within4 = spread(study, objective.scene(), r, 4.0);
  if (study.has_model_sigma()) {
    // The same runs scored with the observations' sigma alone.
    DesignResult alone = r;
    alone.best = -1;
    for (size_t k = 0; k < alone.runs.size(); ++k) {
      alone.runs[k].chi2 = chi2_observations_only(study, alone.runs[k]);
      if (!alone.runs[k].failed && (alone.best < 0 || alone.runs[k].chi2 < alone.runs[alone.best].chi2))
        alone.best = static_cast<long>(k);
    }
    r.within4_observations = spread(study, objective.scene(), alone, 4.0);
    r.with_model_sigma = true;
  }
  if (design.kind == DesignKind::Morris) {
    MorrisDesign m;
    const size_t per_combo = unit_design(continuous_count(study), design, &m).size();
    for (size_t start = 0; start + per_combo <= r.runs.size(); start += per_combo) {
      std::vector<double> chi2;
      for (size_t k = start; k < start + per_combo; ++k) chi2.push_back(r.runs[k].failed ? NAN : r.runs[k].chi2);
      r.effects.push_back(morris_effects(m, chi2));
    }
  }
  r.cached = objective.progress().cached;
  r.run = objective.progress().run;
  return r;
}

}  // namespace ddafit::inverse
