// The misfit of a point of parameter space: chi^2 = sum(((sim - obs)/sigma)^2) over the
// observations. Every forward run goes through here, so this is where runs are cached,
// counted, timed, and where the best point seen is kept (optimisers are not trusted to
// return it: COBYLA-like methods return their last point, and Ceres its last accepted).
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

// Misfit given to a run that failed or could not be set up: large, finite, and rising
// away from the study's start point so that a local method is led back to runnable ground.
constexpr double kFailedMisfit = 1e6;

struct Evaluation {
  std::vector<double> values;     // one per study parameter (levels included)
  double chi2 = 0.0;
  std::vector<double> simulated;  // one per observation (NaN when the run failed)
  std::vector<double> residuals;  // one per observation; zero for a limit that holds
  bool failed = false;
  bool cached = false;            // served from the cache file (an earlier process)
  std::string message;            // why it failed
  std::vector<std::string> point_names;  // the run's measure points, in scene order
  double wall_seconds = 0.0;      // of the forward run (as recorded in the cache when cached)
};

// What the progress line shows.
struct Progress {
  long evaluations = 0;  // objective calls that needed a distinct point
  long failed = 0;       // of which the forward run failed
  long running = 0;      // forward runs under way in a batch (jobs, MPI workers)
  long cached = 0;       // of which served from the cache file
  long run = 0;          // of which forward runs made by this process
  double best_chi2 = 0.0;  // over the whole study so far
  double mean_run_seconds = 0.0;
  long planned = 0;      // evaluations the study plans (levels x budget + profile)
  double eta_seconds = 0.0;
};

class Objective {
 public:
  Objective(const Study& study, EvaluationCache& cache, ForwardModel forward);

  // Observers; none may throw.
  std::function<void(const Progress&)> on_progress;
  std::function<void(const std::string&)> on_log;

  Evaluation evaluate(const std::vector<double>& values);

  // The same evaluations as evaluate() on each point in turn, with the forward runs of the
  // points neither seen nor cached made `jobs` at a time on worker threads (objective_batch.cpp).
  // Only the calling thread scores, writes the cache and reports progress, in the order of
  // `points`, so a batch gives the same log, cache and best point as the loop would.
  std::vector<Evaluation> evaluate_batch(const std::vector<std::vector<double>>& points, int jobs);

  // The same with the runs made by `runner` (threads, MPI ranks): it is given the points
  // that need a run and calls `done(i, result, seconds)` for each on the calling thread,
  // in any order, before it returns.
  using RunDone = std::function<void(size_t index, SimulationResult result, double seconds)>;
  using BatchRunner = std::function<void(const std::vector<std::vector<double>>& points, const RunDone& done)>;
  std::vector<Evaluation> evaluate_batch(const std::vector<std::vector<double>>& points, const BatchRunner& runner);
  // How a batch runs its points: the scan command sets an MPI runner under mpirun;
  // unset, batches run on `jobs` threads.
  BatchRunner batch_runner;
  // Forward runs at a time in the batches the inversion makes itself (the profile's grid).
  int jobs = 1;
  // Runs first on each worker thread (the command line sets the thread budget of a run).
  std::function<void()> on_worker_start;

  // The best point since the last reset_best() (one fit, one block-size level).
  void reset_best();
  bool has_best() const { return best_ >= 0; }
  const Evaluation& best() const { return log_.at(best_); }
  // History of the best point's run when this process has it (empty otherwise; the cache
  // holds the histories of points that were best when they ran).
  const std::vector<HistoryRow>& best_history() const { return best_history_; }

  void set_planned(long planned) { planned_ = planned; }
  Progress progress() const;
  const std::vector<Evaluation>& log() const { return log_; }
  // The study's scene, read once; every run of this objective starts from it.
  const StudyScene& scene() const { return scene_; }
  double wall_seconds_run() const { return seconds_run_; }

 private:
  // evaluate() with the forward run already made (`run` non-null) or to be made now.
  Evaluation record(const std::vector<double>& values, SimulationResult* run, double seconds);
  Evaluation score(const std::vector<double>& values, const SimulationSummary& summary) const;
  // The cached run of `key`, unless it cannot be scored: a completed run kept without its
  // ground surface (cached before the cache kept it) when an observation reads the deposit.
  std::optional<CachedRun> usable_cached(const std::string& key) const;

  const Study& study_;
  StudyScene scene_;
  EvaluationCache& cache_;
  ForwardModel forward_;
  std::map<std::string, size_t> seen_;  // point key -> index in log_
  std::vector<Evaluation> log_;
  long best_ = -1;
  std::vector<HistoryRow> best_history_;
  double best_chi2_ = std::numeric_limits<double>::infinity();  // over the whole study, for progress
  long cached_ = 0, run_ = 0, planned_ = 0, failed_ = 0, running_ = 0;
  double seconds_run_ = 0.0, seconds_cached_ = 0.0;
};

// (simulated - value) / sigma where the observation counts (always for Equal; for AtMost
// and AtLeast only when the limit is violated), else 0.
double observation_residual(const Observation& o, double simulated, double sigma);

// chi^2 of an evaluation's simulated values with each observation's own sigma, leaving its
// model_sigma out (the "observations only" reading of a study with model spread).
double chi2_observations_only(const Study& study, const Evaluation& e);

// A summary field by its name (summary_quantities()); NaN for an unknown name.
double summary_value(const PointSummary& point, const std::string& quantity);

}  // namespace ddafit::inverse
