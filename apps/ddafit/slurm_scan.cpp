// `scan --slurm / --task / --collect`: the job folder's work is batch/slurm_jobs.cpp; this
// file prints what happened and chooses the exit code.
#include "apps/ddafit/slurm_scan.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "apps/ddafit/exit_codes.hpp"
#include "batch/slurm_jobs.hpp"
#include "forward/io/run_files.hpp"
#include "inverse/forward_call.hpp"

namespace ddafit::app {

namespace fs = std::filesystem;

int write_slurm_job(const ScanArgs& args, const inverse::Study& study, const std::vector<std::vector<double>>& todo) {
  const std::string dir = fs::absolute(args.slurm_dir).string();
  if (todo.empty()) {
    if (const std::string problem = io::prepare_output_folder(dir); !problem.empty()) {
      std::cerr << problem << "\n";
      return kExitBadInput;
    }
    std::cout << "every point of the design is in the cache already: nothing to submit\n";
    return kExitSuccess;
  }
  batch::SlurmJob job;
  job.dir = dir;
  job.command = batch::shell_quote(batch::this_executable()) + " scan " +
                batch::shell_quote(fs::absolute(study.path).string());
  job.collect = "ddafit scan STUDY (same design options) --collect " + dir + " --out OUT";
  job.threads = args.threads > 0 ? args.threads : 1;
  job.array_limit = args.array_limit;
  if (const std::string problem = batch::write_slurm_job(job, todo); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("wrote {}/job.sh: {} tasks, at most {} at a time\nsubmit: sbatch {}/job.sh\n"
                           "then:   the same scan command with --collect {} --out OUT\n",
                           dir, todo.size(), args.array_limit, dir, dir);
  return kExitSuccess;
}

int run_slurm_task(const ScanArgs& args, const inverse::Study& study) {
  const batch::SlurmTask task = batch::run_slurm_task(args.task_dir, args.task_index, study);
  if (!task.problem.empty()) {
    std::cerr << task.problem << "\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("point {}: {} in {:.1f} s\n", args.task_index,
                           task.run.summary.status == RunStatus::Completed ? "completed" : task.run.summary.message,
                           task.seconds);
  return kExitSuccess;
}

long collect_slurm_results(const ScanArgs& args, const inverse::Study& study, const std::string& model_version) {
  const fs::path dir(args.collect_dir);
  if (!fs::is_regular_file(dir / "points.txt")) {
    std::cerr << dir.string() << ": --collect: no points.txt here (not a folder written by scan --slurm)\n";
    return -1;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return -1;
  }
  inverse::EvaluationCache cache((fs::path(args.out) / "evaluations.sqlite").string(), model_version,
                                 inverse::scene_input_hash(study));
  const batch::Collected c = batch::collect_slurm_results(dir.string(), study, cache);
  for (const std::string& line : c.skipped) std::cerr << line << "\n";
  std::cout << fmt::format("collected {} of {} results into {}/evaluations.sqlite", c.loaded, c.points, args.out);
  if (c.missing > 0)
    std::cout << fmt::format("; {} without a result (not run, cancelled or failed): run the scan with --slurm again "
                             "for those (the cache holds the rest)", c.missing);
  std::cout << "\n";
  return c.missing;
}

}  // namespace ddafit::app
