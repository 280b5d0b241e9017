// `ddafit simulate SCENE --ensemble K`: K realisations of the scene (forward/perturb.hpp),
// their spread per measure point and quantity, realisation 0's history and summary as a
// plain `simulate` writes them, and a chart of every member.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/ensemble_slurm.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/ensemble_runs.hpp"
#include "batch/mpi_pool.hpp"
#include "batch/thread_budget.hpp"
#include "forward/model_revision.hpp"
#include "forward/io/scene_reader.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "forward/analysis/ensemble.hpp"
#include "forward/io/gnuplot.hpp"
#include "forward/io/run_files.hpp"
#include "forward/io/run_json.hpp"
#include "forward/perturb.hpp"

namespace ddafit::app {
namespace {

namespace fs = std::filesystem;

// ensemble.png: each member's largest total displacement against its peak total speed,
// one colour per measure point: the spread at a glance. Data in ensemble_points.dat, one
// block per point.
bool plot_ensemble(const fs::path& dir, const std::vector<SimulationResult>& members, const std::string& title,
                   std::string& reason) {
  std::vector<std::string> names;
  for (const SimulationResult& m : members)
    for (const PointSummary& p : m.summary.points)
      if (std::find(names.begin(), names.end(), p.name) == names.end()) names.push_back(p.name);
  {
    auto data = fmt::output_file((dir / "ensemble_points.dat").string());
    for (const std::string& name : names) {
      data.print("# {}\n", name);
      for (const SimulationResult& m : members)
        for (const PointSummary& p : m.summary.points)
          if (p.name == name && m.summary.status == RunStatus::Completed)
            data.print("{:.9g} {:.9g}\n", p.max_total_displacement, p.peak_total_velocity);
      data.print("\n\n");
    }
  }
  const std::string script = (dir / "ensemble.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set terminal pngcairo size 1000,700 font ',11'\nset output '{}'\n", (dir / "ensemble.png").string());
    gp.print("set key outside right\nset grid\nset title '{}: {} realisations' noenhanced\n", title, members.size());
    gp.print("set xlabel 'largest total displacement (m)'\nset ylabel 'peak total speed (m/s)'\nplot ");
    for (size_t k = 0; k < names.size(); ++k)
      gp.print("{}'{}' index {} using 1:2 with points pt 7 ps 1.2 title '{}' noenhanced", k ? ", " : "",
               (dir / "ensemble_points.dat").string(), k, names[k]);
    gp.print("\n");
  }
  return io::run_gnuplot(script, "ensemble.json and ensemble.csv", reason);
}

// Under mpirun: realisation 0 on this rank (its history is written here) while ranks
// 1..K-1 run the others, each in a child process (batch/mpi_pool.hpp).
void run_on_ranks(const Scene& nudged, const std::vector<int>& todo, const SimulateArgs& args,
                  const std::function<void(int, SimulationResult, double)>& finished) {
  const batch::MpiWorld world{args.mpi_rank, args.mpi_size};
  std::vector<std::vector<double>> points;
  for (const int k : todo)
    if (k > 0) points.push_back({static_cast<double>(k)});
  std::mutex mutex;
  std::thread local;
  if (!todo.empty() && todo.front() == 0)
    local = std::thread([&] {
      batch::set_worker_threads(std::max(1, args.threads));
      SimulationResult r = simulate(nudged);
      const double seconds = r.summary.profile.total;
      std::lock_guard<std::mutex> lock(mutex);
      finished(0, std::move(r), seconds);
    });
  batch::mpi_batch_runner(world)(points, [&](size_t i, SimulationResult r, double seconds) {
    std::lock_guard<std::mutex> lock(mutex);
    finished(static_cast<int>(points[i].front()), std::move(r), seconds);
  });
  batch::mpi_release_workers(world);
  if (local.joinable()) local.join();
}

}  // namespace

int run_ensemble_command(const SimulateArgs& args, const Scene& scene, const std::string& label) {
  const fs::path dir(args.out);
  Scene nudged = scene;
  nudged.options.jitter_ratio = args.jitter;
  // Every realisation is cached in OUT/evaluations.sqlite as it ends, under the model
  // revision, the scene as read (after --set) with the jitter, and its number: --resume
  // runs only the realisations not there (a larger K after a smaller one, or an
  // interrupted ensemble).
  std::unique_ptr<inverse::EvaluationCache> cache;
  const std::string cache_path = (dir / "evaluations.sqlite").string();
  try {
    cache = std::make_unique<inverse::EvaluationCache>(
        cache_path, std::string(DDAFIT_VERSION) + "+" + kModelRevision,
        inverse::text_hash({io::scene_to_yaml(nudged), fmt::format("jitter={:a}", args.jitter)}));
  } catch (const inverse::CacheError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  }
  bool resume = args.resume;
  if (!args.collect_dir.empty()) {
    const long missing = collect_ensemble_results(args, *cache);
    if (missing < 0) return kExitBadInput;
    if (missing > 0) return kExitRunFailed;
    resume = true;  // every realisation is now in the cache: the ensemble comes from it
  }
  if (!resume && cache->count() > 0) {
    std::cerr << cache_path << ": holds " << cache->count()
              << " realisations of this scene from an earlier run; add --resume to reuse them, or remove the file "
                 "to start over\n";
    return kExitBadInput;
  }
  std::vector<SimulationResult> members(static_cast<size_t>(args.ensemble));
  std::vector<int> todo;
  for (int k = 0; k < args.ensemble; ++k) {
    // Realisation 0's history.csv and summary.json were written beside the cache when it ran.
    const bool files = k > 0 || (fs::exists(dir / "history.csv") && fs::exists(dir / "summary.json"));
    if (const auto hit = cache->find(realisation_key(k)); hit && files) members[k] = hit->result;
    else todo.push_back(k);
  }
  if (!args.slurm_dir.empty()) return write_ensemble_job(args, todo);
  if (!args.quiet && todo.size() < members.size())
    std::cerr << fmt::format("{} of {} realisations from {}\n", members.size() - todo.size(), members.size(), cache_path);
  std::string write_problem;
  const auto finished = [&](int k, SimulationResult r, double seconds) {
    if (k == 0 && r.summary.status != RunStatus::InvalidScene) {
      try {  // as soon as it ends, so that an interrupted ensemble keeps them with the cache
        io::write_history_csv((dir / "history.csv").string(), scene, r);
        io::write_summary_json((dir / "summary.json").string(), label, r);
      } catch (const std::exception& ex) {
        write_problem = args.out + ": --out: " + ex.what();
      }
    }
    if (r.summary.status != RunStatus::Interrupted) cache->store(realisation_key(k), r, seconds, false);
    if (!args.quiet) {
      std::string line = fmt::format("realisation {:>3}: {}", k, io::status_name(r.summary.status));
      if (!r.summary.points.empty()) {
        const PointSummary& p = r.summary.points.front();
        line += fmt::format(", {} max |u| {:.3f} m, max |v| {:.3f} m/s", p.name, p.max_total_displacement,
                            p.peak_total_velocity);
      }
      std::cerr << line << fmt::format(" ({:.1f} s)\n", seconds);
    }
    members[k] = std::move(r);
  };
  if (args.mpi_size > 1) {
    run_on_ranks(nudged, todo, args, finished);
  } else if (!todo.empty()) {
    batch::EnsembleRuns runs = batch::ensemble_runs(args.ensemble, args.jobs, args.threads);
    runs.realisations = todo;
    runs.on_member = [&](int k, const SimulationResult& r) { finished(k, r, r.summary.profile.total); };
    batch::run_ensemble(nudged, runs);
  }
  if (members.front().summary.status == RunStatus::InvalidScene) {
    std::cerr << label << ": " << members.front().summary.message << "\n";
    return kExitBadInput;
  }
  if (!write_problem.empty()) {
    std::cerr << write_problem << "\n";
    return kExitBadInput;
  }
  std::vector<SimulationSummary> summaries;
  for (const SimulationResult& m : members) summaries.push_back(m.summary);
  EnsembleSummary e = summarise_ensemble(summaries);
  e.jitter_ratio = args.jitter > 0.0 ? args.jitter : kJitterRatio;
  try {
    io::write_ensemble_json((dir / "ensemble.json").string(), label, e);
    io::write_ensemble_csv((dir / "ensemble.csv").string(), members);
  } catch (const std::exception& ex) {
    std::cerr << args.out << ": --out: " << ex.what() << "\n";
    return kExitBadInput;
  }
  for (const std::string& f : e.failures) std::cerr << label << ": " << f << "\n";
  if (e.completed == 0) {
    std::cerr << label << ": no realisation completed\n";
    return kExitRunFailed;
  }
  std::string reason;
  if (!plot_ensemble(dir, members, label, reason)) std::cerr << "note: chart not drawn: " << reason << "\n";
  if (!args.quiet) {
    std::cout << fmt::format("{} of {} realisations completed; mean +- standard deviation [range]\n", e.completed,
                             e.members);
    for (const EnsemblePoint& p : e.points)
      for (size_t q = 0; q < p.quantities.size(); ++q) {
        if (kPointQuantities[q].flag) continue;
        const Spread& s = p.quantities[q];
        std::cout << fmt::format("{:<10} {:<26} {:>12.4f} +- {:<10.4f} [{:.4f}, {:.4f}] {}\n", p.name,
                                 kPointQuantities[q].name, s.mean, s.standard_deviation, s.low, s.high,
                                 kPointQuantities[q].unit);
      }
    std::cout << "wrote " << (dir / "ensemble.json").string() << ", ensemble.csv and realisation 0's history.csv and "
              << "summary.json\n";
  }
  return kExitSuccess;
}

}  // namespace ddafit::app
