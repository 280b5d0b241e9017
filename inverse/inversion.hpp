// The back-analysis as a whole: fit every block-size level, profile the degradation
// parameter at the best level for the bounding friction, and take the Ceres covariance
// there as a secondary diagnostic. run_inversion() does no printing; the report writer
// (report.hpp) and the command line turn an InversionSummary into files and text.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "inverse/fit.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/model_spread.hpp"
#include "inverse/multi_fidelity.hpp"
#include "inverse/objective.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

struct InversionOptions {
  std::string out_dir = "ddafit-invert";  // the cache (evaluations.sqlite) lives here
  bool resume = false;  // reuse the cache's evaluations; without it an existing cache is an error
  int budget = 0;       // objective calls per fit; 0 = the study's method.budget
  std::string model_version = "unknown";  // part of the cache key: a new version never reuses runs
  std::function<void(const Progress&)> on_progress;  // after every evaluation; must not throw
  std::function<void(const std::string&)> on_log;    // failed runs and other notes; must not throw
  int jobs = 1;  // forward runs at a time where points are independent (scan designs and profiles)
  std::function<void()> on_worker_start;  // first thing on each worker thread (its thread budget)
  Objective::BatchRunner batch_runner;    // where batches run instead (MPI workers under mpirun)
};

// The part of the options that runs a study's model-spread ensemble (model_spread.hpp).
inline ModelSpreadRuns spread_runs(const InversionOptions& o) { return {o.jobs, o.on_worker_start, o.on_log, o.batch_runner}; }

// Set-up problems (the cache cannot be opened, or exists without --resume): one line.
struct InversionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct LevelFit {
  std::vector<double> start;  // all parameters: the study's starts at this level
  FitResult fit;
  Evaluation best;            // the best point's misfit, simulated values and residuals
  std::vector<HistoryRow> history;  // of the best run, when this process or the cache has it
};

// One side of a Delta-chi^2 interval: where the profile crosses chi2_min + threshold.
struct ProfileRange {
  double threshold = 0.0;               // 1 or 4
  double low = 0.0, high = 0.0;         // parameter values
  double mu_low = 0.0, mu_high = 0.0;   // residual friction coefficient at high, low p
  bool low_at_bound = false, high_at_bound = false;  // the profile never rose that far
};

struct ProfilePoint {
  double value = 0.0;  // the profiled parameter
  double chi2 = 0.0;
  double chi2_observations = 0.0;  // the same run scored with the observations' sigma alone
  double mu = 0.0;
  bool failed = false;
  std::vector<double> values;  // the whole point (others at best, or re-fitted)
};

// mu_b = tan(phi_p - i): i = p/100 phi_p for a degradation_percent parameter (seed Eq. 2-3
// with full degradation), i = the value for a roughness_angle parameter.
struct BoundingFriction {
  bool available = false;
  std::string why_not;       // when not available
  int parameter = -1;        // study parameter profiled
  std::string interface;     // interface name
  double peak_angle = 0.0;   // phi_p, deg, from the resolved scene at the best point
  double best_value = 0.0;
  double mu_best = 0.0;
  bool reoptimized = false;  // others re-fitted at each scan point (else fixed at best)
  std::vector<ProfilePoint> profile;  // sorted by value
  ProfileRange delta1, delta4;
  // Under method.levels multi_fidelity: the profile is the coarse level's runs corrected
  // towards the fine level (InversionSummary::fidelity), not runs of the fine level.
  bool corrected = false;
  // When observations carry a model_sigma: the same ranges with the observations' sigma
  // alone, read off the same runs (the bisection refines delta1/delta4's crossings; these
  // are interpolated between the profile's points, exactly so where chi2 is quadratic).
  bool with_model_sigma = false;
  ProfileRange delta1_observations, delta4_observations;
};

struct CovarianceReport {
  bool computed = false;
  std::vector<int> parameters;  // study parameter of each row/column
  std::vector<std::vector<double>> matrix;  // physical units
  std::vector<double> standard_deviation;
  double condition_number = 0.0;  // of the weighted Jacobian (largest / smallest singular value)
  double mu_standard_deviation = 0.0;  // linearised, for the profiled parameter (0 if none)
  std::vector<std::string> warnings;
};

struct InversionSummary {
  std::vector<Observation> observations;  // as fitted: model_sigma measured where asked
  std::vector<LevelFit> levels;
  int best_level = -1;
  BoundingFriction friction;
  FidelityCorrection fidelity;  // method.levels multi_fidelity: the fine runs and the correction
  CovarianceReport covariance;
  long evaluations = 0, cached = 0, run = 0;  // distinct points; from the cache; run now
  int budget = 0;  // objective calls allowed per fit (the study's, or --budget)
  long history_reruns = 0;  // forward runs repeated only to draw the best fit's curve
  double wall_seconds = 0.0;
  double run_seconds = 0.0;  // of it, in forward runs
  std::string model_version, scene_hash, cache_path;
  std::vector<std::string> notes;  // failed runs and warnings, as logged
};

// The evaluation cache in options.out_dir (the folder is created): refused with an
// InversionError when it holds runs and options.resume is not set. *path gets its file.
std::unique_ptr<EvaluationCache> open_cache(const Study& study, const InversionOptions& options, std::string* path);
// The options' observers and batch settings, onto an objective.
void apply_options(Objective& objective, const InversionOptions& options);

// mu_b for a value of the profiled parameter.
double residual_friction(const Study& study, int parameter, double peak_angle, double value);

InversionSummary run_inversion(const Study& study, const InversionOptions& options,
                               const ForwardModel& forward = run_forward);

// A 1-D scan of one parameter from lower to upper, the others at their starts (the first
// level), through the same cache rules as run_inversion (scan.cpp).
struct ScanResult {
  int parameter = -1;
  std::vector<Evaluation> points;
  long cached = 0, run = 0;
  std::string cache_path;
};
ScanResult run_scan(const Study& study, const InversionOptions& options, const std::string& parameter, int points,
                    const ForwardModel& forward = run_forward);
// The points of that scan: `points` values of `parameter` from lower to upper.
std::vector<std::vector<double>> profile_points(const Study& study, int parameter, int points);

// The parts, for tests.
// The connected range of the profiled parameter around the best completed point where
// chi^2 stays within threshold of it, crossings interpolated in sqrt(Delta chi^2). Failed
// runs are skipped: they say nothing about the fit there.
ProfileRange profile_range(const std::vector<ProfilePoint>& profile, double threshold);

// How a profile scores a point: the objective's own run (the default), or a model of it
// (multi_fidelity.hpp: the coarse run corrected towards the fine level).
using ProfileScore = std::function<Evaluation(const std::vector<double>& values)>;
BoundingFriction profile_friction(Objective& objective, const Study& study, const std::vector<double>& best,
                                  int parameter, int points, bool reoptimize, int budget,
                                  const ProfileScore& score = {});
// method.levels multi_fidelity after the coarse level's fit (out.levels[0]): the coarse
// profile, the fine runs, the corrected profile; adds the fine level to out.levels and sets
// out.friction and out.fidelity (fidelity_levels.cpp).
void run_multi_fidelity(Objective& objective, const Study& study, int profiled, int scan, InversionSummary& out);
CovarianceReport covariance_at(Objective& objective, const Study& study, const std::vector<double>& best,
                               int profiled);

}  // namespace ddafit::inverse
