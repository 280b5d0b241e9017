// `ddafit simulate SCENE --ensemble K` on a SLURM cluster, as scans do it
// (batch/slurm_jobs.hpp): --slurm DIR writes one array task per realisation the output
// folder's cache does not hold, each task (--task DIR --task-index I, run by job.sh)
// writes its result file, and --collect DIR loads them into the cache, from which the
// ensemble is written as on one machine.
#pragma once

#include <string>
#include <vector>

#include "apps/ddafit/commands.hpp"
#include "inverse/evaluation_cache.hpp"

namespace ddafit::app {

// The cache key of realisation k in an ensemble's cache.
std::string realisation_key(int k);

// DIR/points.txt (one realisation per line) and DIR/job.sh, whose tasks run this command
// line's scene, --set and --jitter again. Prints what to do next; returns the exit code.
int write_ensemble_job(const SimulateArgs& args, const std::vector<int>& todo);

// One task: realisation (line task_index of DIR/points.txt) of `nudged`, written to
// DIR/results/INDEX.json (and realisation 0's history.csv and summary.json to DIR/results/).
int run_ensemble_task(const SimulateArgs& args, const Scene& scene, const Scene& nudged, const std::string& label);

// Loads DIR/results into `cache` and copies realisation 0's files into the output folder.
// Returns the realisations without a result, or -1 (a folder not written by --slurm).
long collect_ensemble_results(const SimulateArgs& args, inverse::EvaluationCache& cache);

}  // namespace ddafit::app
