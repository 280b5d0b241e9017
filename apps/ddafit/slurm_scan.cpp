#include "apps/ddafit/slurm_scan.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "apps/ddafit/exit_codes.hpp"
#include "apps/ddafit/output_files.hpp"
#include "apps/ddafit/run_codec.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"

namespace ddafit::app {
namespace {

namespace fs = std::filesystem;

std::string this_executable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("ddafit") : self.string();
}

std::vector<std::vector<double>> read_points(const fs::path& file) {
  std::vector<std::vector<double>> points;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::vector<double> values;
    for (double v; fields >> v;) values.push_back(v);
    points.push_back(values);
  }
  return points;
}

}  // namespace

int write_slurm_job(const ScanArgs& args, const inverse::Study& study, const std::vector<std::vector<double>>& todo) {
  const fs::path dir = fs::absolute(args.slurm_dir);
  if (const std::string problem = prepare_output_folder(dir.string()); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  if (todo.empty()) {
    std::cout << "every point of the design is in the cache already: nothing to submit\n";
    return kExitSuccess;
  }
  fs::create_directories(dir / "results");
  fs::create_directories(dir / "logs");
  {
    std::ofstream points(dir / "points.txt");
    for (const auto& x : todo) {
      for (size_t k = 0; k < x.size(); ++k) points << (k ? " " : "") << inverse::exact_text(x[k]);
      points << "\n";
    }
  }
  const int threads = args.threads > 0 ? args.threads : 1;
  std::string command = this_executable() + " scan " + fs::absolute(study.path).string() + " --task " + dir.string() +
                        " --task-index $SLURM_ARRAY_TASK_ID --threads " + std::to_string(threads);
  {
    std::ofstream job(dir / "job.sh");
    job << "#!/bin/bash\n"
        << "#SBATCH --job-name=ddafit-scan\n"
        << fmt::format("#SBATCH --array=0-{}%{}\n", todo.size() - 1, args.array_limit)
        << "#SBATCH --cpus-per-task=" << threads << "\n"
        << "#SBATCH --output=" << (dir / "logs" / "task_%a.out").string() << "\n"
        << "# Written by ddafit scan --slurm: one task per point still to run (points.txt).\n"
        << "# Submit: sbatch " << (dir / "job.sh").string() << "\n"
        << "# Then:   ddafit scan STUDY (same design options) --collect " << dir.string() << " --out OUT\n"
        << "srun --ntasks=1 " << command << "\n";
  }
  fs::permissions(dir / "job.sh", fs::perms::owner_exec, fs::perm_options::add);
  std::cout << fmt::format("wrote {}/job.sh: {} tasks, at most {} at a time\nsubmit: sbatch {}/job.sh\n"
                           "then:   the same scan command with --collect {} --out OUT\n",
                           dir.string(), todo.size(), args.array_limit, dir.string(), dir.string());
  return kExitSuccess;
}

int run_slurm_task(const ScanArgs& args, const inverse::Study& study) {
  const fs::path dir(args.task_dir);
  const std::vector<std::vector<double>> points = read_points(dir / "points.txt");
  if (args.task_index < 0 || args.task_index >= static_cast<long>(points.size())) {
    std::cerr << (dir / "points.txt").string() << ": --task-index " << args.task_index << ": no such point (it has "
              << points.size() << ")\n";
    return kExitBadInput;
  }
  const std::vector<double>& values = points[static_cast<size_t>(args.task_index)];
  if (values.size() != study.parameters.size()) {
    std::cerr << (dir / "points.txt").string() << ": line " << args.task_index + 1 << ": " << values.size()
              << " values for the study's " << study.parameters.size() << " parameters\n";
    return kExitBadInput;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const SimulationResult run = inverse::StudyScene(study).run(values, inverse::run_forward);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json j;
  j["values"] = values;
  j["run"] = encode_run(run, seconds);
  // Written whole, then renamed: a task cancelled mid-write leaves no half result.
  const fs::path file = dir / "results" / (std::to_string(args.task_index) + ".json");
  const fs::path partial = file.string() + ".partial";
  std::ofstream(partial) << j.dump() << "\n";
  fs::rename(partial, file);
  std::cout << fmt::format("point {}: {} in {:.1f} s\n", args.task_index,
                           run.summary.status == RunStatus::Completed ? "completed" : run.summary.message, seconds);
  return kExitSuccess;
}

long collect_slurm_results(const ScanArgs& args, const inverse::Study& study, const std::string& model_version) {
  const fs::path dir(args.collect_dir);
  if (!fs::is_regular_file(dir / "points.txt")) {
    std::cerr << dir.string() << ": --collect: no points.txt here (not a folder written by scan --slurm)\n";
    return -1;
  }
  const std::vector<std::vector<double>> points = read_points(dir / "points.txt");
  if (const std::string problem = prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return -1;
  }
  inverse::EvaluationCache cache((fs::path(args.out) / "evaluations.sqlite").string(), model_version,
                                 inverse::scene_input_hash(study));
  long loaded = 0, missing = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    const fs::path file = dir / "results" / (std::to_string(k) + ".json");
    std::ifstream in(file);
    if (!in) {
      ++missing;
      continue;
    }
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      double seconds = 0.0;
      const SimulationResult run = decode_run(j["run"].get<std::string>(), &seconds);
      cache.store(inverse::point_key(study, j["values"].get<std::vector<double>>()), run, seconds, false);
      ++loaded;
    } catch (const std::exception& e) {
      std::cerr << file.string() << ": not a result of ddafit scan --task (" << e.what() << "); skipped\n";
      ++missing;
    }
  }
  std::cout << fmt::format("collected {} of {} results into {}/evaluations.sqlite", loaded, points.size(), args.out);
  if (missing > 0)
    std::cout << fmt::format("; {} without a result (not run, cancelled or failed): run the scan with --slurm again "
                             "for those (the cache holds the rest)", missing);
  std::cout << "\n";
  return missing;
}

}  // namespace ddafit::app
