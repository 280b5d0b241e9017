// `ddafit scan`: chi^2 and the simulated observations along one parameter, the others at
// their starts (first level). The same grid the profile uses, without a fit first: a quick
// look at how the misfit depends on a parameter before spending a budget on it.
#include <filesystem>

#include "inverse/evaluation_cache.hpp"
#include "inverse/inversion.hpp"

namespace ddafit::inverse {

std::vector<std::vector<double>> profile_points(const Study& study, int parameter, int points) {
  std::vector<double> x;
  for (const Parameter& p : study.parameters) x.push_back(p.discrete() ? p.levels.front() : p.start);
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
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw InversionError(options.out_dir + ": --out: cannot create the folder (" + ec.message() + ")");
  out.cache_path = (std::filesystem::path(options.out_dir) / "evaluations.sqlite").string();
  EvaluationCache cache(out.cache_path, options.model_version, scene_input_hash(study));
  if (!options.resume && cache.count() > 0)
    throw InversionError(out.cache_path + ": holds " + std::to_string(cache.count()) +
                         " evaluations from an earlier run; add --resume to reuse them, or remove the file");
  Objective objective(study, cache, forward);
  objective.on_progress = options.on_progress;
  objective.on_log = options.on_log;
  objective.set_planned(points);
  objective.on_worker_start = options.on_worker_start;
  objective.batch_runner = options.batch_runner;
  objective.jobs = options.jobs;
  out.points = objective.evaluate_batch(profile_points(study, out.parameter, points), options.jobs);
  out.cached = objective.progress().cached;
  out.run = objective.progress().run;
  return out;
}

}  // namespace ddafit::inverse
