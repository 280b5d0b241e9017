#include "inverse/model_spread.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <mutex>
#include <thread>

#include "forward/analysis/ensemble.hpp"

namespace ddafit::inverse {
namespace {

std::string realisation_key(const Study& study, const std::vector<double>& x, int k) {
  return point_key(study, x) + (k > 0 ? ";realisation=" + std::to_string(k) : "");
}

bool wants_spread(const Study& study) {
  return std::any_of(study.observations.begin(), study.observations.end(),
                     [](const Observation& o) { return o.model_sigma_from_ensemble; });
}

std::vector<double> spread_start(const Study& study) {
  std::vector<double> at;
  for (const Parameter& p : study.parameters) at.push_back(p.discrete() ? p.first_model_level() : p.start);
  return at;
}

}  // namespace

std::vector<std::vector<double>> model_spread_points(const Study& study) {
  std::vector<std::vector<double>> points;
  if (!wants_spread(study)) return points;
  const std::vector<double> at = spread_start(study);
  for (int k = 0; k < study.ensemble; ++k) {
    points.push_back(at);
    if (k > 0) points.back().push_back(static_cast<double>(k));
  }
  return points;
}

bool split_spread_point(const Study& study, const std::vector<double>& point, std::vector<double>& values,
                        int& realisation) {
  const size_t n = study.parameters.size();
  values.assign(point.begin(), point.begin() + static_cast<long>(std::min(n, point.size())));
  realisation = 0;
  if (point.size() == n) return true;
  if (point.size() != n + 1 || point[n] < 1.0 || point[n] != std::floor(point[n])) return false;
  realisation = static_cast<int>(point[n]);
  return true;
}

std::string model_spread_key(const Study& study, const std::vector<double>& point) {
  std::vector<double> values;
  int k = 0;
  split_spread_point(study, point, values, k);
  return realisation_key(study, values, k);
}

ModelSpread measure_model_spread(const Study& study, const ModelSpreadRuns& options, EvaluationCache& cache,
                                 const ForwardModel& forward) {
  ModelSpread out;
  out.study = study;
  if (!wants_spread(study)) return out;
  out.at = spread_start(study);
  const int members = study.ensemble;
  std::vector<SimulationSummary> summaries(static_cast<size_t>(members));
  std::vector<int> todo;
  for (int k = 0; k < members; ++k) {
    if (const auto hit = cache.find(realisation_key(study, out.at, k))) {
      summaries[k] = hit->result.summary;
      ++out.cached;
    } else {
      todo.push_back(k);
    }
  }
  // The runs share nothing; the cache is written by this thread only, as each ends.
  const StudyScene scene(study);
  std::mutex mutex;
  const auto finished = [&](int k, SimulationResult run, double seconds, const char* where) {
    std::lock_guard<std::mutex> lock(mutex);
    cache.store(realisation_key(study, out.at, k), run, seconds, false);
    summaries[k] = std::move(run.summary);
    ++out.run;
    if (options.on_log)
      options.on_log(fmt::format("model spread: realisation {} of {} {} in {:.1f} s{}", k, members,
                                 summaries[k].status == RunStatus::Completed ? "completed" : "failed", seconds, where));
  };
  if (options.batch_runner && !todo.empty()) {
    std::vector<std::vector<double>> points;
    for (const int k : todo) {
      points.push_back(out.at);
      points.back().push_back(static_cast<double>(k));
    }
    options.batch_runner(points, [&](size_t i, SimulationResult run, double seconds) {
      finished(todo[i], std::move(run), seconds, " on a worker rank");
    });
  } else {
    std::atomic<size_t> next{0};
    const auto work = [&] {
      if (options.on_worker_start && options.jobs > 1) options.on_worker_start();
      for (size_t i = next++; i < todo.size(); i = next++) {
        const auto t0 = std::chrono::steady_clock::now();
        SimulationResult run = scene.run(out.at, forward, todo[i]);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        finished(todo[i], std::move(run), seconds, "");
      }
    };
    std::vector<std::thread> workers;
    for (int w = 1; w < std::min<int>(std::max(options.jobs, 1), static_cast<int>(todo.size())); ++w)
      workers.emplace_back(work);
    work();
    for (std::thread& t : workers) t.join();
  }

  // The statistics of forward/analysis/ensemble, over the members that completed.
  const EnsembleSummary spread = summarise_ensemble(summaries);
  out.members = spread.members;
  out.completed = spread.completed;
  for (const std::string& failure : spread.failures) out.notes.push_back("model spread: " + failure);
  for (size_t k = 0; k < out.study.observations.size(); ++k) {
    Observation& o = out.study.observations[k];
    if (!o.model_sigma_from_ensemble) continue;
    const Spread* s = find_spread(spread, o.point, o.quantity);
    o.model_sigma = s ? s->standard_deviation : 0.0;
    out.notes.push_back(fmt::format("observations[{}] ({} {}): model_sigma = {:.4g} from {} of {} realisations "
                                    "(mean {:.4g}); sigma_eff = {:.4g} against sigma {:.4g}",
                                    k, o.point, o.quantity, o.model_sigma, spread.completed, members,
                                    s ? s->mean : NAN, o.effective_sigma(), o.sigma));
  }
  return out;
}

}  // namespace ddafit::inverse
