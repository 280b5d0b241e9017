#include "inverse/inversion.hpp"
#include "inverse/model_spread.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "inverse/evaluation_cache.hpp"

namespace ddafit::inverse {

namespace {

// Every combination of the discrete parameters' levels, each as a full starting point.
std::vector<std::vector<double>> level_starts(const Study& study) {
  std::vector<double> base;
  for (const Parameter& p : study.parameters) base.push_back(p.discrete() ? p.levels.front() : p.start);
  std::vector<std::vector<double>> out{base};
  for (size_t j = 0; j < study.parameters.size(); ++j) {
    const Parameter& p = study.parameters[j];
    if (!p.discrete()) continue;
    std::vector<std::vector<double>> next;
    for (const auto& point : out)
      for (double level : p.levels) {
        next.push_back(point);
        next.back()[j] = level;
      }
    out = std::move(next);
  }
  return out;
}

}  // namespace

double residual_friction(const Study& study, int parameter, double peak_angle, double value) {
  const std::string& key = study.parameters.at(parameter).key;
  const bool percent = key.find("degradation_percent") != std::string::npos;
  const double residual_angle = percent ? peak_angle * (1.0 - value / 100.0) : peak_angle - value;
  return std::tan(residual_angle * M_PI / 180.0);
}

std::unique_ptr<EvaluationCache> open_cache(const Study& study, const InversionOptions& options, std::string* path) {
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw InversionError(options.out_dir + ": --out: cannot create the folder (" + ec.message() + ")");
  *path = (std::filesystem::path(options.out_dir) / "evaluations.sqlite").string();
  auto cache = std::make_unique<EvaluationCache>(*path, options.model_version, scene_input_hash(study));
  if (!options.resume && cache->count() > 0)
    throw InversionError(*path + ": holds " + std::to_string(cache->count()) +
                         " evaluations of this study's scene from an earlier run; add --resume to reuse them, or "
                         "remove the file to start over");
  return cache;
}

void apply_options(Objective& objective, const InversionOptions& options) {
  objective.jobs = options.jobs;
  objective.on_worker_start = options.on_worker_start;
  objective.batch_runner = options.batch_runner;
  objective.on_progress = options.on_progress;
  objective.on_log = options.on_log;
}

InversionSummary run_inversion(const Study& given, const InversionOptions& options, const ForwardModel& forward) {
  const auto t0 = std::chrono::steady_clock::now();
  InversionSummary out;
  out.model_version = options.model_version;
  out.scene_hash = scene_input_hash(given);
  std::unique_ptr<EvaluationCache> cache_file = open_cache(given, options, &out.cache_path);
  EvaluationCache& cache = *cache_file;
  // A `model_sigma: ensemble` is measured once, at the start, before any fit.
  const ModelSpread spread = measure_model_spread(given, spread_runs(options), cache, forward);
  for (const std::string& line : spread.notes) {
    out.notes.push_back(line);
    if (options.on_log) options.on_log(line);
  }
  const Study& study = spread.study;
  out.observations = study.observations;

  Objective objective(study, cache, forward);
  apply_options(objective, options);
  objective.on_log = [&](const std::string& line) {
    out.notes.push_back(line);
    if (options.on_log) options.on_log(line);
  };
  const int budget = options.budget > 0 ? options.budget : study.method.budget;
  out.budget = budget;
  const std::vector<std::vector<double>> starts = level_starts(study);
  const int profiled = profile_parameter(study);
  const int scan = profiled >= 0 ? study.profile.points : 0;
  const long per_scan_point = study.profile.reoptimize ? std::max(1, budget / 2) : 1;
  const long fine = study.method.coarse_to_fine && study.method.fine_budget > 0 ? study.method.fine_budget : budget;
  const bool multi_fidelity = study.method.multi_fidelity;
  objective.set_planned(multi_fidelity ? budget + 2 * scan + 2 * study.method.fine_runs
                                       : budget + static_cast<long>(starts.size() - 1) * fine + scan * per_scan_point);

  std::vector<bool> free;
  for (const Parameter& p : study.parameters) free.push_back(!p.discrete());
  for (const auto& level_start : starts) {
    LevelFit level;
    level.start = level_start;
    int level_budget = budget;
    // Coarse to fine: the continuous values start where the last (coarser) level ended.
    std::vector<double> start = level_start;
    if (study.method.coarse_to_fine && !out.levels.empty() && !out.levels.back().best.failed) {
      for (size_t j = 0; j < start.size(); ++j)
        if (free[j]) start[j] = out.levels.back().best.values[j];
      if (study.method.fine_budget > 0) level_budget = study.method.fine_budget;
    }
    level.fit = fit(objective, study, start, free, level_budget);
    if (objective.has_best()) level.best = objective.best();
    level.history = objective.best_history();
    out.levels.push_back(std::move(level));
    // Coarse to fine reports the finest level; independent levels the best chi^2.
    if (study.method.coarse_to_fine || out.best_level < 0 ||
        out.levels.back().best.chi2 < out.levels[out.best_level].best.chi2)
      out.best_level = static_cast<int>(out.levels.size()) - 1;
    // Multi-fidelity fits the coarse level alone; its fine runs come with the profile.
    if (multi_fidelity) break;
  }
  if (multi_fidelity && !out.levels.front().best.failed) run_multi_fidelity(objective, study, profiled, scan, out);
  LevelFit& best = out.levels[out.best_level];

  if (multi_fidelity) {
    if (out.levels.front().best.failed) out.friction.why_not = "the coarse level's fit found no completed run";
  } else if (profiled < 0) {
    out.friction.why_not = "no *.degradation_percent or *.roughness_angle parameter of an interface to profile";
  } else if (scan == 0) {
    out.friction.why_not = "profile.points is 0";
  } else {
    out.friction = profile_friction(objective, study, best.best.values, profiled, scan, study.profile.reoptimize,
                                    per_scan_point);
  }
  // ddafit keeps the best point it saw: a profile point may beat the fit (the fit stops
  // within step_tolerance resolutions of the minimum, the scan may land closer).
  // (Not under multi_fidelity: its profile points are coarse runs, corrected.)
  for (const ProfilePoint& pt : out.friction.profile) {
    if (multi_fidelity || pt.failed || pt.chi2 >= best.best.chi2) continue;
    best.best = objective.evaluate(pt.values);
    best.history.clear();
    out.friction.best_value = pt.value;
    out.friction.mu_best = pt.mu;
  }
  if (multi_fidelity)
    out.covariance.warnings.push_back(
        "not computed under multi_fidelity: its differences would need fine runs per parameter; the profile bounds "
        "the friction");
  else if (!best.best.failed)
    out.covariance = covariance_at(objective, study, best.best.values, profiled);

  // The best fit's history for the velocity-distance curve: from this process, else the
  // cache, else one more forward run (counted apart, so resumed studies stay comparable).
  if (best.history.empty() && !best.best.failed) {
    const std::string key = point_key(study, best.best.values);
    if (auto hit = cache.find(key); hit && hit->has_history) {
      best.history = std::move(hit->result.history);
    } else {
      const auto started = std::chrono::steady_clock::now();
      SimulationResult again = objective.scene().run(best.best.values, forward);
      ++out.history_reruns;
      cache.store(key, again, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), true);
      best.history = std::move(again.history);
    }
  }
  const Progress p = objective.progress();
  out.evaluations = p.evaluations;
  out.cached = p.cached;
  out.run = p.run;
  out.run_seconds = objective.wall_seconds_run();
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace ddafit::inverse
