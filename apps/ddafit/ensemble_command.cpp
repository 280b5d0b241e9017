// `ddafit simulate SCENE --ensemble K`: K realisations of the scene (forward/perturb.hpp),
// their spread per measure point and quantity, realisation 0's history and summary as a
// plain `simulate` writes them, and a chart of every member.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/ensemble_runs.hpp"
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

}  // namespace

int run_ensemble_command(const SimulateArgs& args, const Scene& scene, const std::string& label) {
  const fs::path dir(args.out);
  batch::EnsembleRuns runs = batch::ensemble_runs(args.ensemble, args.jobs, args.threads);
  runs.on_member = [&](int k, const SimulationResult& r) {
    if (args.quiet) return;
    std::string line = fmt::format("realisation {:>3}: {}", k, io::status_name(r.summary.status));
    if (!r.summary.points.empty()) {
      const PointSummary& p = r.summary.points.front();
      line += fmt::format(", {} max |u| {:.3f} m, max |v| {:.3f} m/s", p.name, p.max_total_displacement,
                          p.peak_total_velocity);
    }
    std::cerr << line << fmt::format(" ({:.1f} s)\n", r.summary.profile.total);
  };
  Scene nudged = scene;
  nudged.options.jitter_ratio = args.jitter;
  const std::vector<SimulationResult> members = batch::run_ensemble(nudged, runs);
  if (members.front().summary.status == RunStatus::InvalidScene) {
    std::cerr << label << ": " << members.front().summary.message << "\n";
    return kExitBadInput;
  }
  std::vector<SimulationSummary> summaries;
  for (const SimulationResult& m : members) summaries.push_back(m.summary);
  EnsembleSummary e = summarise_ensemble(summaries);
  e.jitter_ratio = args.jitter > 0.0 ? args.jitter : kJitterRatio;
  try {
    io::write_history_csv((dir / "history.csv").string(), scene, members.front());
    io::write_summary_json((dir / "summary.json").string(), label, members.front());
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
