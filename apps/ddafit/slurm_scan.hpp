// Scans on a SLURM cluster: `scan --slurm DIR` writes a job array (one task per point the
// cache does not hold yet), each task writes its result file, and `scan --collect DIR`
// loads the results into the evaluation cache of --out, after which the scan's report is
// made from the cache as on one machine.
#pragma once

#include <string>
#include <vector>

#include "apps/ddafit/commands.hpp"
#include "inverse/study.hpp"

namespace ddafit::app {

// DIR/points.txt (one point per line, exact values), DIR/job.sh (sbatch --array=0-(N-1)%K,
// each task `srun ddafit scan STUDY --task DIR --task-index $SLURM_ARRAY_TASK_ID`),
// DIR/results/ and DIR/logs/. Returns an exit code; prints how to submit and collect.
int write_slurm_job(const ScanArgs& args, const inverse::Study& study, const std::vector<std::vector<double>>& todo);

// One array task: line --task-index of DIR/points.txt to DIR/results/INDEX.json.
int run_slurm_task(const ScanArgs& args, const inverse::Study& study);

// Loads DIR/results/*.json into the cache in --out. Returns the number of points of
// DIR/points.txt without a result (-1 when DIR is not a job folder), after printing it.
long collect_slurm_results(const ScanArgs& args, const inverse::Study& study, const std::string& model_version);

}  // namespace ddafit::app
