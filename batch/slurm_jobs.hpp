// Scans (and ensembles, apps/ddafit/ensemble_slurm.cpp) on a SLURM cluster, as a job folder: `write_slurm_job` writes one array task per
// point the cache does not hold yet, each task (`run_slurm_task`) writes its result file,
// and `collect_slurm_results` loads the results into an evaluation cache, from which the
// scan's report is made as on one machine. The command line (apps/ddafit/slurm_scan.cpp)
// only prints.
#pragma once

#include <string>
#include <vector>

#include "inverse/evaluation_cache.hpp"
#include "inverse/study.hpp"

namespace ddafit::batch {

struct SlurmJob {
  std::string dir;         // the job folder, created if needed
  // What each task runs, up to its task arguments: "ddafit scan /abs/study.yaml" or
  // "ddafit simulate /abs/scene.yaml --set ... --ensemble K" (shell-quoted where needed).
  std::string command;
  std::string collect;     // the line job.sh gives as its next step (a comment)
  int threads = 1;         // per task (#SBATCH --cpus-per-task)
  int array_limit = 4;     // tasks at a time (sbatch --array=0-(N-1)%K)
};

// This ddafit binary's absolute path (what job.sh runs), and a word quoted for bash.
std::string this_executable();
std::string shell_quote(const std::string& word);

// DIR/points.txt (one point per line, exact values), DIR/job.sh (each task runs
// `srun COMMAND --task DIR --task-index $SLURM_ARRAY_TASK_ID --threads T`), DIR/results/
// and DIR/logs/. Returns "" or the one-line problem (a folder that cannot be written).
std::string write_slurm_job(const SlurmJob& job, const std::vector<std::vector<double>>& todo);

// The points of DIR/points.txt, in task order.
std::vector<std::vector<double>> read_slurm_points(const std::string& dir);

struct SlurmTask {
  std::string problem;  // one line when the index or the point does not fit the study
  SimulationResult run;
  double seconds = 0.0;
};
// One array task: line `index` of DIR/points.txt, run and written to DIR/results/INDEX.json
// (written whole, then renamed: a cancelled task leaves no half result).
SlurmTask run_slurm_task(const std::string& dir, long index, const inverse::Study& study);

struct Collected {
  long points = 0;                    // in DIR/points.txt
  long loaded = 0;                    // results stored in the cache
  long missing = 0;                   // points without a usable result
  std::vector<std::string> skipped;   // "FILE: not a result of ..." for files that do not read
};
// Loads DIR/results/*.json into `cache`.
Collected collect_slurm_results(const std::string& dir, const inverse::Study& study, inverse::EvaluationCache& cache);

}  // namespace ddafit::batch
