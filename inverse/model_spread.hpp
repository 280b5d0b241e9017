// The model's own spread, measured: a study whose observations say `model_sigma: ensemble`
// runs the study's ensemble (`ensemble: K` realisations, forward/perturb.hpp) at its
// starting point once, before the fit, and each such observation's model_sigma becomes the
// standard deviation of its simulated quantity over the completed members.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/objective.hpp"

namespace ddafit::inverse {

struct ModelSpread {
  Study study;                      // the given study with every measured model_sigma filled in
  std::vector<double> at;           // the point the ensemble ran at (the study's start)
  int members = 0, completed = 0;   // 0 when nothing was measured
  long run = 0, cached = 0;         // forward runs made now, and found in the cache
  std::vector<std::string> notes;   // one line per measured observation, and failures
};

// How the realisations run (InversionOptions gives these: spread_runs()).
struct ModelSpreadRuns {
  int jobs = 1;                                     // runs at a time
  std::function<void()> on_worker_start;            // first thing on each extra thread
  std::function<void(const std::string&)> on_log;   // one line per run ended
  // Where the realisations run instead of threads (MPI worker ranks under mpirun): each
  // point it is given is the start point with the realisation appended as one more value.
  Objective::BatchRunner batch_runner;
};

// Realisations run `runs.jobs` at a time; each is cached under the start point's key
// with ";realisation=K" appended (realisation 0 is the start point's own run), so a
// resumed study measures nothing twice. A study with no `model_sigma: ensemble` comes back
// unchanged, with nothing run.
// The points that measure the study's model spread, one per realisation, in order:
// realisation 0 is the start point itself, realisation k >= 1 the start point with k
// appended as one more value (as MPI ranks and SLURM tasks receive them). Empty when no
// observation asks for `model_sigma: ensemble`.
std::vector<std::vector<double>> model_spread_points(const Study& study);
// The cache key of such a point: the start point's key, with ";realisation=K" for k >= 1.
std::string model_spread_key(const Study& study, const std::vector<double>& point);

// A point as MPI ranks and SLURM tasks receive it, split: the parameter values, and the
// realisation (0 for a point of the study's own size; k >= 1 from one value more). False
// when the point has neither size or its last value is not a whole k >= 1.
bool split_spread_point(const Study& study, const std::vector<double>& point, std::vector<double>& values,
                        int& realisation);

ModelSpread measure_model_spread(const Study& study, const ModelSpreadRuns& runs, EvaluationCache& cache,
                                 const ForwardModel& forward);

}  // namespace ddafit::inverse
