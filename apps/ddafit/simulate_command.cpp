#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/ensemble_slurm.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/mpi_pool.hpp"
#include "batch/stop_signals.hpp"
#include "apps/ddafit/clock_text.hpp"
#include "forward/io/run_files.hpp"
#include "apps/ddafit/plots.hpp"
#include "apps/ddafit/vtk_writer.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/mirror.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit::app {

bool parse_overrides(const std::vector<std::string>& sets, std::vector<std::pair<std::string, std::string>>& out) {
  for (const std::string& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::cerr << "ddafit: --set: expected KEY=VALUE (e.g. mesh.block_size=12.1), got '" << s << "'\n";
      return false;
    }
    out.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return true;
}

bool load_scene(const std::string& path, const std::vector<std::string>& sets, Scene& scene) {
  std::vector<std::pair<std::string, std::string>> overrides;
  if (!parse_overrides(sets, overrides)) return false;
  try {
    scene = io::read_scene(path, overrides);
  } catch (const io::SceneReadError& e) {
    std::cerr << e.what() << "\n";
    return false;
  }
  return true;
}

int run_simulate(const SimulateArgs& args) {
  Scene scene;
  std::string label = args.scene;
  if (args.scene.empty()) {
    // The built-in default: the seed's incline check with degradation (i = 5 deg).
    verification::InclineSetup setup;
    setup.roughness_angle = 5.0;
    scene = verification::incline_scene(setup);
    label = "built-in incline (phi = 25 deg, i = 5 deg)";
    if (!args.sets.empty()) {
      // --set applies to the built-in scene as to a file: written out and read back with
      // the overrides, so every value goes through the same checks.
      std::vector<std::pair<std::string, std::string>> overrides;
      if (!parse_overrides(args.sets, overrides)) return kExitBadInput;
      try {
        scene = io::parse_scene(io::scene_to_yaml(scene), "built-in incline", "", overrides);
      } catch (const io::SceneReadError& e) {
        std::cerr << e.what() << "\n";
        return kExitBadInput;
      }
    }
  } else {
    if (!load_scene(args.scene, args.sets, scene)) return kExitBadInput;
  }
  if ((!args.slurm_dir.empty() || !args.collect_dir.empty() || !args.task_dir.empty()) && args.ensemble <= 0) {
    std::cerr << "ddafit simulate: --slurm, --collect and --task belong to --ensemble K\n";
    return kExitBadInput;
  }
  if (args.ensemble > 0 && !args.task_dir.empty()) {
    // One task of a --slurm job array: writes into the job folder only.
    Scene nudged = scene;
    nudged.options.jitter_ratio = args.jitter;
    return run_ensemble_task(args, scene, nudged, label);
  }
  if (args.ensemble > 0 && args.mpi_rank > 0) {
    // A worker rank of `mpirun ... simulate --ensemble`: realisations for rank 0 until it
    // says stop; it writes and prints nothing.
    Scene nudged = scene;
    nudged.options.jitter_ratio = args.jitter;
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    batch::mpi_ensemble_worker(nudged, args.threads > 0 ? args.threads : std::max(1, cores / args.mpi_size),
                               args.run_timeout);
    return kExitSuccess;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  if (args.mirror && (args.ensemble > 0 || args.vtk_interval > 0.0)) {
    std::cerr << "ddafit simulate: --mirror writes the history and summary read back unmirrored; it does not combine "
                 "with --ensemble or --vtk-interval\n";
    return kExitBadInput;
  }
  if (args.ensemble > 0) return run_ensemble_command(args, scene, label);
  std::error_code ec;
  // The scene as run: the file's, or its mirror image (forward/mirror.hpp).
  const Scene run_scene = args.mirror ? mirrored_scene(scene) : scene;
  if (args.mirror) label += " (mirrored)";

  SimulationHooks hooks;
  std::string vtk_problem;
  if (args.vtk_interval > 0.0) {
    const std::filesystem::path vtk_dir = std::filesystem::path(args.out) / "vtk";
    std::filesystem::create_directories(vtk_dir, ec);
    hooks.on_output = [&, vtk_dir, next = 0.0, count = 0](double t, const BlockSystem& system) mutable {
      if (t + 1e-9 < next || !vtk_problem.empty()) return;
      try {
        write_state_vtk((vtk_dir / fmt::format("blocks_{:05d}.vtk", count++)).string(), system, t);
      } catch (const std::exception& e) {
        vtk_problem = e.what();
      }
      next += args.vtk_interval;
    };
  }
  // The free blocks at the last output, for --plots' picture of the final configuration.
  std::vector<std::vector<Vec2>> final_blocks;
  const auto vtk_output = hooks.on_output;
  if (args.plots) {
    hooks.on_output = [&, vtk_output](double t, const BlockSystem& system) {
      if (vtk_output) vtk_output(t, system);
      final_blocks.clear();
      for (const Block& b : system.blocks)
        if (!b.fixed) {
          final_blocks.emplace_back(system.vertices.begin() + b.first_vertex,
                                    system.vertices.begin() + b.first_vertex + b.vertex_count);
          if (args.mirror)
            for (Vec2& v : final_blocks.back()) v.x() = -v.x();  // drawn as the scene's own
        }
    };
  }
  if (!args.quiet) {
    hooks.on_progress = [start = std::chrono::steady_clock::now()](double t, double duration) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      // Wall time per simulated second has been steady enough over a slide to extrapolate.
      const std::string eta = t > 0.0 ? "ETA " + clock_text(wall * (duration - t) / t) : "";
      std::cerr << fmt::format("\r  t = {:.3f} / {:.3f} s ({:.0f} %)  wall {}  {}   ", t, duration,
                               100.0 * t / duration, clock_text(wall), eta)
                << std::flush;
    };
  }
  batch::note_stop_signals();
  hooks.should_stop = [] { return batch::stop_signal() != 0; };
  SimulationResult result = simulate(run_scene, hooks);
  if (args.mirror) unmirror_history(result.history);
  if (!args.quiet) std::cerr << "\r" << std::string(72, ' ') << "\r";

  const std::string history = (std::filesystem::path(args.out) / "history.csv").string();
  const std::string summary = (std::filesystem::path(args.out) / "summary.json").string();
  try {
    io::write_history_csv(history, scene, result);
    io::write_summary_json(summary, label, result);
  } catch (const std::exception& e) {
    std::cerr << args.out << ": --out: " << e.what() << "\n";
    return kExitBadInput;
  }

  const SimulationSummary& s = result.summary;
  // --quiet prints errors only; the warnings stay in summary.json.
  if (!args.quiet)
    for (const std::string& w : s.warnings) std::cerr << label << ": warning: " << w << "\n";
  if (s.status == RunStatus::InvalidScene) {
    std::cerr << label << ": " << s.message << "\n";
    return kExitBadInput;
  }
  if (s.status == RunStatus::Failed) {
    std::cerr << label << ": simulation failed: " << s.message << "\n";
    return kExitRunFailed;
  }
  if (s.status == RunStatus::Interrupted) {
    std::cerr << label << ": " << s.message << "; the history so far and the summary are in " << args.out << "\n";
    return batch::exit_code_for(batch::stop_signal());
  }
  if (!vtk_problem.empty()) std::cerr << args.out << ": VTK snapshots stopped: " << vtk_problem << "\n";
  if (args.plots) {
    std::string reason;
    if (!plot_history(args.out, scene, label, reason) || !plot_configuration(args.out, scene, final_blocks, label, reason))
      std::cerr << "note: charts not drawn: " << reason << "\n";
    try {
      write_run_report(args.out, label, result);
    } catch (const std::exception& e) {
      std::cerr << args.out << ": --out: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  if (!args.quiet) {
    std::cout << fmt::format("{} steps, {} open-close iterations, {} step cuts, {} penalty raises, {:.2f} s wall\n",
                             s.run.steps, s.run.open_close_iterations, s.run.step_cuts, s.run.penalty_raises,
                             s.profile.total);
    std::cout << fmt::format("{:<10} {:>12} {:>12} {:>12} {:>12} {:>10} {:>8}\n", "point", "max|ux| m", "max|u| m",
                             "max|vx| m/s", "max|v| m/s", "duration s", "stopped");
    for (const PointSummary& p : s.points)
      std::cout << fmt::format("{:<10} {:>12.4f} {:>12.4f} {:>12.4f} {:>12.4f} {:>10.2f} {:>8}\n", p.name,
                               p.max_lateral_displacement, p.max_total_displacement, p.peak_lateral_velocity,
                               p.peak_total_velocity, p.duration, p.stopped ? "yes" : "no");
    std::cout << "wrote " << history << " and " << summary << "\n";
  }
  return kExitSuccess;
}

}  // namespace ddafit::app
