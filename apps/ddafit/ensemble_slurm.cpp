#include "apps/ddafit/ensemble_slurm.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/ddafit/exit_codes.hpp"
#include "batch/slurm_jobs.hpp"
#include "forward/io/run_files.hpp"
#include "forward/io/run_json.hpp"
#include "forward/simulation.hpp"

namespace ddafit::app {
namespace {

namespace fs = std::filesystem;

// Written whole, then renamed: a task killed by scancel or a time limit leaves no half file.
void write_whole(const fs::path& file, const std::string& text) {
  const fs::path partial = file.string() + ".partial";
  std::ofstream(partial) << text;
  fs::rename(partial, file);
}

}  // namespace

std::string realisation_key(int k) { return "realisation=" + std::to_string(k); }

int write_ensemble_job(const SimulateArgs& args, const std::vector<int>& todo) {
  const std::string dir = fs::absolute(args.slurm_dir).string();
  if (todo.empty()) {
    std::cout << "every realisation is in " << args.out << "/evaluations.sqlite already: nothing to submit\n";
    return kExitSuccess;
  }
  batch::SlurmJob job;
  job.dir = dir;
  // The task reads the scene as this command did: the same file, --set and --jitter.
  job.command = batch::shell_quote(batch::this_executable()) + " simulate " +
                batch::shell_quote(fs::absolute(args.scene).string());
  for (const std::string& s : args.sets) job.command += " --set " + batch::shell_quote(s);
  job.command += fmt::format(" --ensemble {}", args.ensemble);
  if (args.jitter > 0.0) job.command += " --jitter " + fmt::format("{:.17g}", args.jitter);
  job.collect = "the same simulate command with --collect " + dir + " --out " + args.out;
  job.threads = args.threads > 0 ? args.threads : 1;
  job.array_limit = args.array_limit;
  std::vector<std::vector<double>> points;
  for (const int k : todo) points.push_back({static_cast<double>(k)});
  if (const std::string problem = batch::write_slurm_job(job, points); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("wrote {}/job.sh: {} realisations, at most {} at a time\nsubmit: sbatch {}/job.sh\n"
                           "then:   {}\n",
                           dir, todo.size(), args.array_limit, dir, job.collect);
  return kExitSuccess;
}

int run_ensemble_task(const SimulateArgs& args, const Scene& scene, const Scene& nudged, const std::string& label) {
  const fs::path dir(args.task_dir);
  const std::string points_file = (dir / "points.txt").string();
  const std::vector<std::vector<double>> points = batch::read_slurm_points(dir.string());
  if (args.task_index < 0 || args.task_index >= static_cast<long>(points.size())) {
    std::cerr << fmt::format("{}: --task-index {}: no such realisation (it has {})\n", points_file, args.task_index,
                             points.size());
    return kExitBadInput;
  }
  const std::vector<double>& line = points[static_cast<size_t>(args.task_index)];
  const int k = line.size() == 1 ? static_cast<int>(line.front()) : -1;
  if (k < 0 || k >= args.ensemble || line.front() != k) {
    std::cerr << fmt::format("{}: line {}: not a realisation of this --ensemble {}\n", points_file,
                             args.task_index + 1, args.ensemble);
    return kExitBadInput;
  }
  Scene member = nudged;
  member.options.realisation = k;
  const auto t0 = std::chrono::steady_clock::now();
  const SimulationResult run = simulate(member);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fs::create_directories(dir / "results");
  if (k == 0 && run.summary.status != RunStatus::InvalidScene) {
    io::write_history_csv((dir / "results" / "history.csv.partial").string(), scene, run);
    fs::rename(dir / "results" / "history.csv.partial", dir / "results" / "history.csv");
    io::write_summary_json((dir / "results" / "summary.json.partial").string(), label, run);
    fs::rename(dir / "results" / "summary.json.partial", dir / "results" / "summary.json");
  }
  nlohmann::json j;
  j["realisation"] = k;
  j["run"] = io::encode_run(run, seconds);
  write_whole(dir / "results" / (std::to_string(args.task_index) + ".json"), j.dump() + "\n");
  std::cout << fmt::format("realisation {}: {} in {:.1f} s\n", k, io::status_name(run.summary.status), seconds);
  return kExitSuccess;
}

long collect_ensemble_results(const SimulateArgs& args, inverse::EvaluationCache& cache) {
  const fs::path dir(args.collect_dir);
  if (!fs::is_regular_file(dir / "points.txt")) {
    std::cerr << dir.string() << ": --collect: no points.txt here (not a folder written by simulate --slurm)\n";
    return -1;
  }
  const std::vector<std::vector<double>> points = batch::read_slurm_points(dir.string());
  long loaded = 0, missing = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const fs::path file = dir / "results" / (std::to_string(i) + ".json");
    std::ifstream in(file);
    if (!in) {
      ++missing;
      continue;
    }
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      double seconds = 0.0;
      const SimulationResult run = io::decode_run(j["run"].get<std::string>(), &seconds);
      const int k = j["realisation"].get<int>();
      if (k == 0) {  // its history and summary, without which the cache's row is not used
        fs::copy_file(dir / "results" / "history.csv", fs::path(args.out) / "history.csv",
                      fs::copy_options::overwrite_existing);
        fs::copy_file(dir / "results" / "summary.json", fs::path(args.out) / "summary.json",
                      fs::copy_options::overwrite_existing);
      }
      cache.store(realisation_key(k), run, seconds, false);
      ++loaded;
    } catch (const std::exception& e) {
      std::cerr << file.string() << ": not a result of ddafit simulate --task (" << e.what() << "); skipped\n";
      ++missing;
    }
  }
  std::cout << fmt::format("collected {} of {} results into {}/evaluations.sqlite", loaded, points.size(), args.out);
  if (missing > 0)
    std::cout << fmt::format("; {} without a result (not run, cancelled or failed): run the command with --slurm "
                             "again for those (the cache holds the rest)", missing);
  std::cout << "\n";
  return missing;
}

}  // namespace ddafit::app
