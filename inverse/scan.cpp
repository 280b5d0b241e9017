// `ddafit scan`: chi^2 and the simulated observations along one parameter, the others at
// their starts (first level). The same grid the profile uses, without a fit first: a quick
// look at how the misfit depends on a parameter before spending a budget on it.
#include <filesystem>

#include "inverse/model_spread.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/inversion.hpp"

namespace ddafit::inverse {

std::vector<std::vector<double>> profile_points(const Study& study, int parameter, int points) {
  std::vector<double> x;
  for (const Parameter& p : study.parameters) x.push_back(p.discrete() ? p.first_model_level() : p.start);
  const Parameter& p = study.parameters[parameter];
  std::vector<std::vector<double>> out;
  for (int k = 0; k < points; ++k) {
    x[parameter] = p.lower + (p.upper - p.lower) * k / (points - 1);
    out.push_back(x);
  }
  return out;
}

ScanResult run_scan(const Study& study, const InversionOptions& options, const std::string& parameter, int points,
                    const ForwardModel& forward) {
  ScanResult out;
  for (size_t k = 0; k < study.parameters.size(); ++k)
    if (study.parameters[k].name == parameter) out.parameter = static_cast<int>(k);
  if (out.parameter < 0 || study.parameters[out.parameter].discrete())
    throw InversionError(study.path + ": --parameter: '" + parameter + "' is not a continuous parameter of the study");
  if (points < 2) throw InversionError(study.path + ": --points: give at least 2");
  const std::unique_ptr<EvaluationCache> cache = open_cache(study, options, &out.cache_path);
  // A `model_sigma: ensemble` is measured once, before the scan; chi2 then uses sigma_eff.
  const ModelSpread spread = measure_model_spread(study, spread_runs(options), *cache, forward);
  for (const std::string& line : spread.notes)
    if (options.on_log) options.on_log(line);
  Objective objective(spread.study, *cache, forward);
  apply_options(objective, options);
  objective.set_planned(points);
  out.points = objective.evaluate_batch(profile_points(study, out.parameter, points), options.jobs);
  out.cached = objective.progress().cached;
  out.run = objective.progress().run;
  return out;
}

}  // namespace ddafit::inverse
