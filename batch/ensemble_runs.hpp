// Runs the K realisations of one scene (forward/perturb.hpp), `jobs` at a time on worker
// threads: `ddafit simulate --ensemble K --jobs J` and a study's measured model spread.
#pragma once

#include <functional>
#include <vector>

#include "forward/run_summary.hpp"
#include "forward/scene.hpp"

namespace ddafit::batch {

struct EnsembleRuns {
  int members = 8;          // realisations 0 .. members - 1
  std::vector<int> realisations;  // the ones to run; empty: all of them
  int jobs = 1;             // runs at a time
  int threads_per_run = 1;  // OpenMP threads of each run when jobs > 1
  // Called on the calling thread as each member ends, in any order; may be empty.
  std::function<void(int realisation, const SimulationResult& run)> on_member;
};

// `members` realisations `jobs` at a time, the thread budget (`threads`; 0 = the core count)
// shared out between the jobs.
EnsembleRuns ensemble_runs(int members, int jobs, int threads);

// Each member's result, realisation k at index k (a default result where it was not run). Members share nothing, so the numbers do
// not depend on `jobs` (tests/test_ensemble.cpp).
std::vector<SimulationResult> run_ensemble(const Scene& scene, const EnsembleRuns& runs);

}  // namespace ddafit::batch
