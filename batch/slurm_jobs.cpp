#include "batch/slurm_jobs.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "forward/io/run_files.hpp"
#include "forward/io/run_json.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/model_spread.hpp"

namespace ddafit::batch {
namespace fs = std::filesystem;

std::string this_executable() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("ddafit") : self.string();
}

std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<std::vector<double>> read_slurm_points(const std::string& dir) {
  std::vector<std::vector<double>> points;
  std::ifstream in(fs::path(dir) / "points.txt");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::vector<double> values;
    for (double v; fields >> v;) values.push_back(v);
    points.push_back(values);
  }
  return points;
}

std::string write_slurm_job(const SlurmJob& job, const std::vector<std::vector<double>>& todo) {
  const fs::path dir = fs::absolute(job.dir);
  if (std::string problem = io::prepare_output_folder(dir.string()); !problem.empty()) return problem;
  fs::create_directories(dir / "results");
  fs::create_directories(dir / "logs");
  {
    std::ofstream points(dir / "points.txt");
    for (const auto& x : todo) {
      for (size_t k = 0; k < x.size(); ++k) points << (k ? " " : "") << inverse::exact_text(x[k]);
      points << "\n";
    }
  }
  const std::string command = job.command + " --task " + shell_quote(dir.string()) +
                              " --task-index $SLURM_ARRAY_TASK_ID --threads " + std::to_string(job.threads);
  {
    std::ofstream script(dir / "job.sh");
    script << "#!/bin/bash\n"
           << "#SBATCH --job-name=ddafit\n"
           << fmt::format("#SBATCH --array=0-{}%{}\n", todo.size() - 1, job.array_limit)
           << "#SBATCH --cpus-per-task=" << job.threads << "\n"
           << "#SBATCH --output=" << (dir / "logs" / "task_%a.out").string() << "\n"
           << "# Written by ddafit --slurm: one task per point still to run (points.txt).\n"
           << "# Submit: sbatch " << (dir / "job.sh").string() << "\n"
           << "# Then:   " << job.collect << "\n"
           << "srun --ntasks=1 " << command << "\n";
  }
  fs::permissions(dir / "job.sh", fs::perms::owner_exec, fs::perm_options::add);
  return {};
}

SlurmTask run_slurm_task(const std::string& dir, long index, const inverse::Study& study) {
  SlurmTask task;
  const std::string points_file = (fs::path(dir) / "points.txt").string();
  const std::vector<std::vector<double>> points = read_slurm_points(dir);
  if (index < 0 || index >= static_cast<long>(points.size())) {
    task.problem = fmt::format("{}: --task-index {}: no such point (it has {})", points_file, index, points.size());
    return task;
  }
  const std::vector<double>& values = points[static_cast<size_t>(index)];
  // n values: a point of the design; n + 1: a realisation of the model spread at the start
  // point (inverse/model_spread.hpp).
  std::vector<double> parameters;
  int realisation = 0;
  if (!inverse::split_spread_point(study, values, parameters, realisation)) {
    task.problem = fmt::format("{}: line {}: {} values for the study's {} parameters", points_file, index + 1,
                               values.size(), study.parameters.size());
    return task;
  }
  const auto t0 = std::chrono::steady_clock::now();
  task.run = inverse::StudyScene(study).run(parameters, inverse::run_forward, realisation);
  task.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json j;
  j["values"] = values;
  j["run"] = io::encode_run(task.run, task.seconds);
  const fs::path file = fs::path(dir) / "results" / (std::to_string(index) + ".json");
  const fs::path partial = file.string() + ".partial";
  std::ofstream(partial) << j.dump() << "\n";
  fs::rename(partial, file);
  return task;
}

Collected collect_slurm_results(const std::string& dir, const inverse::Study& study, inverse::EvaluationCache& cache) {
  Collected c;
  const std::vector<std::vector<double>> points = read_slurm_points(dir);
  c.points = static_cast<long>(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    const fs::path file = fs::path(dir) / "results" / (std::to_string(k) + ".json");
    std::ifstream in(file);
    if (!in) {
      ++c.missing;
      continue;
    }
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      double seconds = 0.0;
      const SimulationResult run = io::decode_run(j["run"].get<std::string>(), &seconds);
      cache.store(inverse::model_spread_key(study, j["values"].get<std::vector<double>>()), run, seconds, false);
      ++c.loaded;
    } catch (const std::exception& e) {
      c.skipped.push_back(file.string() + ": not a result of ddafit scan --task (" + e.what() + "); skipped");
      ++c.missing;
    }
  }
  return c;
}

}  // namespace ddafit::batch
