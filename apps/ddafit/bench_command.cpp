// ddafit bench: the forward model's cost across block sizes (the Vajont sections I-X by
// default), one row per size in DIR/bench.csv, and DIR/bench.png, wall time per simulated
// second against block count on log-log axes beside an N^1.2 line.
#include <fmt/format.h>
#include <fmt/os.h>
#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "forward/io/gnuplot.hpp"
#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/run_files.hpp"
#include "apps/ddafit/plots.hpp"
#include "forward/simulation.hpp"

namespace ddafit::app {
namespace {

// Largest resident set of this process so far, MiB (Linux reports KiB).
double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

struct BenchRow {
  double block_size = 0.0;
  int blocks = 0;  // free blocks
  SimulationSummary summary;
  double peak_mib = 0.0;
};

void write_chart(const std::string& dir, const std::vector<BenchRow>& rows, std::string& reason) {
  // The reference line passes through the first row, so its slope reads directly.
  const BenchRow& first = rows.front();
  const double first_cost = first.summary.profile.total / std::max(first.summary.run.simulated_time, 1e-12);
  std::ofstream gp(dir + "/bench.gp");
  gp << "set terminal pngcairo size 900,600\nset output '" << dir << "/bench.png'\n"
     << "set logscale xy\nset grid\nset key top left\n"
     << "set xlabel 'free blocks'\nset ylabel 'wall time per simulated second (s)'\n"
     << "set datafile separator ','\n"
     << "plot '" << dir << "/bench.csv' using 2:($8/$5) every ::1 with linespoints lw 2 title 'ddafit', "
     << first_cost << "*(x/" << first.blocks << ")**1.2 with lines dt 2 title 'N^{1.2} from the first row'\n";
  gp.close();
  io::run_gnuplot(dir + "/bench.gp", "the data files", reason);
}

}  // namespace

int run_bench(const BenchArgs& args) {
  if (args.sizes.empty() || !(args.duration > 0.0)) {
    std::cerr << "ddafit bench: need at least one --sizes value and a positive --duration\n";
    return kExitBadInput;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::vector<BenchRow> rows;
  std::cout << fmt::format("{:>8} {:>7} {:>7} {:>8} {:>9} {:>9} {:>9} {:>8} {:>9}  {}\n", "size (m)", "blocks",
                           "steps", "passes", "wall (s)", "solve (s)", "asm (s)", "contacts", "peak MiB", "status");
  for (double size : args.sizes) {
    std::vector<std::string> sets = args.sets;
    sets.push_back(fmt::format("mesh.block_size={}", size));
    sets.push_back(fmt::format("time.duration={}", args.duration));
    if (!args.integrator.empty()) sets.push_back("time.integrator=" + args.integrator);
    Scene scene;
    if (!load_scene(args.scene, sets, scene)) return kExitBadInput;
    BenchRow row;
    row.block_size = size;
    for (const BlockInput& b : scene.blocks) row.blocks += !b.fixed;
    row.summary = simulate(scene).summary;
    row.peak_mib = peak_memory_mib();
    const StepProfile& p = row.summary.profile;
    const RunCounters& r = row.summary.run;
    std::cout << fmt::format("{:>8} {:>7} {:>7} {:>8} {:>9.2f} {:>9.2f} {:>9.2f} {:>8.2f} {:>9.0f}  {}\n", size,
                             row.blocks, r.steps, r.open_close_iterations, p.total, p.solve, p.assemble,
                             p.find_contacts + p.check_contacts, row.peak_mib,
                             row.summary.status == RunStatus::Completed ? "completed" : row.summary.message)
              << std::flush;
    rows.push_back(std::move(row));
  }
  auto csv = fmt::output_file(args.out + "/bench.csv");
  csv.print("block_size,blocks,steps,open_close_iterations,simulated_time,step_cuts,penalty_raises,wall,"
            "settle,find_contacts,assemble,solve,check_contacts,update,peak_memory_mib,factorizations,"
            "factor_updates,symbolic_analyses,status,integrator,substeps,contact_points_per_step,worst_penetration_ratio\n");
  for (const BenchRow& row : rows) {
    const StepProfile& p = row.summary.profile;
    const RunCounters& r = row.summary.run;
    const SolverReport& solver = row.summary.solver;
    csv.print("{},{},{},{},{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.1f},{},{},{},{},{},{},{:.1f},{:.5f}\n",
              row.block_size, row.blocks, r.steps, r.open_close_iterations, r.simulated_time, r.step_cuts,
              r.penalty_raises, p.total, p.settle, p.find_contacts, p.assemble, p.solve, p.check_contacts, p.update,
              row.peak_mib, r.factorizations, r.factor_updates, r.symbolic_analyses,
              row.summary.status == RunStatus::Completed ? "completed" : "failed", to_string(solver.integrator),
              solver.substeps, static_cast<double>(solver.contact_points) / std::max<double>(1.0, static_cast<double>(r.steps)),
              solver.worst_penetration_ratio);
  }
  csv.close();
  std::string reason;
  write_chart(args.out, rows, reason);
  if (!reason.empty()) std::cerr << "ddafit bench: no chart: " << reason << "\n";
  std::cout << "wrote " << args.out << "/bench.csv" << (reason.empty() ? " and bench.png" : "") << "\n";
  return kExitSuccess;
}

}  // namespace ddafit::app
