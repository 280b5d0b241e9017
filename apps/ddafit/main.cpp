// ddafit: back-analysis of rapid landslides with DDA. This file only parses arguments
// and hands over to one function per subcommand.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "batch/mpi_pool.hpp"
#include "batch/thread_budget.hpp"

namespace {

// "; did you mean 'NAME'?" for the name within three edits of `typed`, else "".
std::string did_you_mean(const std::string& typed, const std::vector<std::string>& names) {
  std::string best;
  size_t best_distance = 4;
  for (const std::string& name : names) {
    // Levenshtein distance, one row at a time.
    std::vector<size_t> row(name.size() + 1);
    for (size_t j = 0; j <= name.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= typed.size(); ++i) {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= name.size(); ++j) {
        const size_t above = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (typed[i - 1] == name[j - 1] ? 0 : 1)});
        diagonal = above;
      }
    }
    if (row[name.size()] < best_distance) best_distance = row[name.size()], best = name;
  }
  return best.empty() ? "" : "; did you mean '" + best + "'?";
}

// A number option in [low, high], with a message in the user's terms (CLI11's own range
// check printed its bounds with six decimals, the largest double as 309 digits).
CLI::Validator within(double low, double high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        double v = 0.0;
        try {
          size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "expected a number, got '" + text + "'";
        } catch (const std::exception&) {
          return "expected a number, got '" + text + "'";
        }
        if (!(v >= low && v <= high))
          return "is " + text + "; must be in [" + CLI::detail::to_string(low) + ", " + CLI::detail::to_string(high) + "]";
        return {};
      },
      "in [" + CLI::detail::to_string(low) + ", " + CLI::detail::to_string(high) + "]");
}

}  // namespace

int main(int argc, char** argv) {
  ddafit::batch::bound_thread_spinning(argv);  // may re-execute once (thread_budget.hpp)
  using namespace ddafit::app;
  CLI::App app{"ddafit: discontinuous deformation analysis for landslide back-analysis"};
  app.set_version_flag("--version", std::string("ddafit ") + DDAFIT_VERSION);
  app.require_subcommand(1);

  SimulateArgs sim;
  CLI::App* simulate = app.add_subcommand("simulate", "run a scene; writes history.csv and summary.json");
  simulate->add_option("scene", sim.scene, "scene file (YAML); without it, the built-in incline case");
  simulate->add_option("--out", sim.out, "output folder")->capture_default_str();
  simulate->add_option("--set", sim.sets, "override a scene value, KEY=VALUE (repeatable)");
  simulate->add_flag("--quiet", sim.quiet, "print errors only (warnings stay in summary.json)");
  simulate->add_option("--vtk-interval", sim.vtk_interval, "write DIR/vtk/blocks_NNNNN.vtk every this many s")
      ->check(within(0.0, 1e6));
  simulate->add_flag("--plots", sim.plots, "draw distance/velocity charts (PNG, needs gnuplot)");
  simulate->add_flag("--mirror", sim.mirror,
                     "run the scene's mirror image (x -> -x) and write its results read back unmirrored: how much "
                     "the answer depends on the order the solver meets the blocks in (docs/speed-accuracy.md)");
  simulate->add_option("--ensemble", sim.ensemble,
                       "run K realisations (0: the scene; k >= 1: free blocks nudged by <= --jitter of their size) and "
                       "write their spread to ensemble.json, ensemble.csv and ensemble.png")
      ->check(CLI::Range(1, 10000));
  simulate->add_option("--jitter", sim.jitter,
                       "--ensemble: the largest nudge of a block, as a fraction of its size (default 1e-6)")
      ->check(CLI::Range(1e-12, 1e-2));
  simulate->add_option("--jobs", sim.jobs, "--ensemble: realisations at a time (jobs x threads <= cores)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  simulate->add_flag("--resume", sim.resume,
                     "--ensemble: reuse the realisations cached in the output folder (evaluations.sqlite) and run "
                     "only the others");
  simulate->add_option("--slurm", sim.slurm_dir,
                       "--ensemble: write a SLURM job array for the realisations not yet cached into this folder");
  simulate->add_option("--array-limit", sim.array_limit, "--slurm: array tasks at a time")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  simulate->add_option("--collect", sim.collect_dir,
                       "--ensemble: load a --slurm folder's results into the cache, then write the ensemble");
  simulate->add_option("--task", sim.task_dir, "(used by --slurm's job.sh) run one realisation of this folder")
      ->group("");
  simulate->add_option("--task-index", sim.task_index, "(used by job.sh) the line of points.txt")->group("");
  simulate->add_option("--run-timeout", sim.run_timeout,
                       "s; --ensemble under mpirun: a realisation past this is killed, retried once")
      ->capture_default_str()
      ->check(within(1.0, 1e7));

  MeshArgs mesh;
  CLI::App* mesh_cmd = app.add_subcommand("mesh", "cut a scene's regions into blocks; writes scene.yaml, VTK, PNG");
  mesh_cmd->add_option("scene", mesh.scene, "scene file (YAML) with regions")->required();
  mesh_cmd->add_option("--out", mesh.out, "output folder")->capture_default_str();
  mesh_cmd->add_option("--set", mesh.sets, "override a scene value, KEY=VALUE (repeatable)");

  PlotArgs pl;
  CLI::App* plot = app.add_subcommand("plot", "draw the charts of a finished run from its history.csv");
  plot->add_option("scene", pl.scene, "the scene the run used (for the point names)")->required();
  plot->add_option("dir", pl.dir, "the run's output folder")->required();
  plot->add_option("--set", pl.sets, "the overrides the run used, KEY=VALUE (repeatable)");
  plot->add_option("--runout-range", pl.observed.runout, "m, LOW HIGH: an estimated lateral runout, drawn as a band")
      ->expected(2)
      ->check(within(0.0, 1e6));
  plot->add_option("--speed-range", pl.observed.peak_speed, "m/s, LOW HIGH: an estimated peak lateral speed, drawn as a band")
      ->expected(2)
      ->check(within(0.0, 1e4));
  plot->add_option("--estimate", pl.observed.label, "whose estimate the bands are (legend text)");

  SledArgs sl;
  CLI::App* sled = app.add_subcommand(
      "sled", "fidelity 0: the free blocks as one flexible sled along the ground, Coulomb friction on its base from "
              "the scene's interface laws; writes sled.csv, sled.json (static friction angle), sled.png");
  sled->add_option("scene", sl.scene, "scene file (YAML)")->required();
  sled->add_option("--out", sl.out, "output folder")->capture_default_str();
  sled->add_option("--set", sl.sets, "override a scene value, KEY=VALUE (repeatable)");

  ImportArgs im;
  CLI::App* import_cmd = app.add_subcommand(
      "import", "a scene from the XML input (DDAML) of the UC Berkeley DDA codes (ntdda): joint lines cut into "
                "blocks, fixed and measured points, materials, joint properties, time step, gravity, penalty");
  import_cmd->add_option("geometry", im.geometry, "geometry file (.geo, DDAML)")->required();
  import_cmd->add_option("--analysis", im.analysis, "analysis file (.ana, DDAML); without it, placeholders are written");
  import_cmd->add_option("--units", im.units,
                         "kN: m, t/m^3, kN/m^3, kPa; SI: m, kg/m^3, N/m^3, Pa (the classic files carry no units)")
      ->required()
      ->check(CLI::IsMember({"kN", "SI"}));
  import_cmd->add_option("--out", im.out, "scene file to write (YAML)")->required();

  AdviseArgs ad;
  CLI::App* advise = app.add_subcommand(
      "advise", "block-size advice: cut the scene's regions at a ladder of block sizes, run each as a small ensemble, "
                "and name the coarsest size whose answer is within the tolerance of the next finer one");
  advise->add_option("scene", ad.scene, "scene file (YAML) with regions")->required();
  advise->add_option("--quantity", ad.quantity, "a point quantity of summary.json")->capture_default_str();
  advise->add_option("--point", ad.point, "measure point name")->required();
  advise->add_option("--sizes", ad.sizes, "block sizes, m (default: 4, 2 and 1 x mesh.block_size)")->delimiter(',');
  advise->add_option("--tolerance", ad.tolerance, "relative change allowed between neighbouring sizes")
      ->capture_default_str()->check(CLI::Range(1e-6, 1.0));
  advise->add_option("--ensemble", ad.members, "realisations per size (their spread widens the tolerance)")
      ->capture_default_str()->check(CLI::Range(1, 64));
  advise->add_option("--jobs", ad.jobs, "realisations at a time")->capture_default_str()->check(CLI::Range(1, 256));
  advise->add_option("--out", ad.out, "output folder for advise.json")->capture_default_str();
  advise->add_option("--set", ad.sets, "override a scene value, KEY=VALUE (repeatable)");

  StableArgs st;
  CLI::App* stable = app.add_subcommand(
      "stable",
      "bisect an interface's friction angle for the stable state: a trial is stable when, over the last "
      "--rest-window s, no measure point is as fast as the scene's rest_speed and the speeds are not rising");
  stable->add_option("scene", st.scene, "scene file (YAML)")->required();
  stable->add_option("--interface", st.interface, "interface whose friction angle is searched")->required();
  stable->add_option("--low", st.options.low, "deg, a value that slides")->capture_default_str()->check(within(0.0, 90.0));
  stable->add_option("--high", st.options.high, "deg, a value that holds")->capture_default_str()->check(within(0.0, 90.0));
  stable->add_option("--tolerance", st.options.tolerance, "deg, width of the final bracket")
      ->capture_default_str()
      ->check(within(1e-6, 90.0));
  stable->add_option("--time", st.options.trial_duration, "s simulated per trial")->capture_default_str()->check(within(1e-6, 1e4));
  stable->add_option("--rest-window", st.options.rest_window, "s at the end of a trial over which the speeds are judged")
      ->capture_default_str()
      ->check(within(1e-6, 1e4));
  stable->add_option("--movement", st.options.max_movement,
                     "m: also require that no point moved further (0 = no such condition)")
      ->capture_default_str()
      ->check(within(0.0, 1e6));
  stable->add_option("--out", st.out, "output folder for stable.json")->capture_default_str();
  stable->add_option("--set", st.sets, "override a scene value, KEY=VALUE (repeatable)");

  InvertArgs inv;
  CLI::App* invert = app.add_subcommand("invert", "back-analysis: fit scene values to observations (docs/back-analysis.md)");
  invert->add_option("study", inv.study,
                     "study file (YAML); without it, the built-in twin study (cases/inverse/twin_study.yaml, "
                     "about half a minute)");
  invert->add_option("--out", inv.out, "output folder: report and evaluation cache")->capture_default_str();
  invert->add_flag("--resume", inv.resume, "reuse the evaluations cached in the output folder");
  invert->add_option("--budget", inv.budget, "objective evaluations per fit (default: the study's method.budget)")
      ->check(CLI::PositiveNumber);
  invert->add_flag("--quiet", inv.quiet, "print nothing but errors");
  invert->add_option("--jobs", inv.jobs, "forward runs at a time where independent (the profile's grid)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  invert->add_flag("--check", inv.check, "read and check the study and its scene, print the plan, run nothing");

  ScanArgs sc;
  CLI::App* scan = app.add_subcommand("scan", "chi2 over a study's parameters: a profile, a grid, a Latin hypercube or Morris");
  scan->add_option("study", sc.study, "study file (YAML)")->required();
  scan->add_option("--design", sc.design, "profile (one parameter), grid, lhs or morris")
      ->capture_default_str()
      ->check(CLI::IsMember({"profile", "grid", "lhs", "morris"}));
  scan->add_option("--parameter", sc.parameter, "profile: the parameter to scan (its name in the study)");
  scan->add_option("--points", sc.points, "profile: points from lower to upper; grid: values per parameter")
      ->capture_default_str()
      ->check(CLI::Range(2, 10000));
  scan->add_option("--samples", sc.samples, "lhs: points")->capture_default_str()->check(CLI::Range(2, 100000));
  scan->add_option("--trajectories", sc.trajectories, "morris: trajectories")->capture_default_str()->check(CLI::Range(2, 10000));
  scan->add_option("--levels", sc.levels, "morris: grid levels (even)")->capture_default_str()->check(CLI::Range(2, 100));
  scan->add_option("--seed", sc.seed, "lhs, morris: random seed (the same seed gives the same points)")
      ->capture_default_str()
      ->check(CLI::Range(0L, 1000000000000L));
  scan->add_option("--jobs", sc.jobs, "forward runs at a time (jobs x threads <= cores)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  scan->add_option("--run-timeout", sc.run_timeout, "s; under mpirun a forward run past this is killed, retried once")
      ->capture_default_str()
      ->check(within(1.0, 1e7));
  scan->add_option("--slurm", sc.slurm_dir, "write a SLURM job array for the points not yet cached into this folder");
  scan->add_option("--array-limit", sc.array_limit, "--slurm: array tasks at a time")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  scan->add_option("--collect", sc.collect_dir, "load a --slurm folder's results into the cache, then report");
  scan->add_option("--task", sc.task_dir, "(used by --slurm's job.sh) run one point of this folder's points.txt")
      ->group("");
  scan->add_option("--task-index", sc.task_index, "(used by job.sh) the point")->group("");
  scan->add_flag("--dry-run", sc.dry_run, "print the plan (runs, cached, estimated wall time) and stop");
  scan->add_option("--out", sc.out, "output folder: runs.csv or scan.csv, report.md and the evaluation cache")
      ->capture_default_str();
  scan->add_flag("--resume", sc.resume, "reuse the evaluations cached in the output folder");

  AnimateArgs an;
  CLI::App* animate = app.add_subcommand("animate", "PNG frames and a GIF of a run's blocks coloured by speed");
  animate->add_option("dir", an.dir, "the run's output folder (simulate --vtk-interval wrote DIR/vtk)")->required();
  animate->add_option("--out", an.out, "output folder (default: DIR/animation)");
  animate->add_option("--times", an.times, "also draw speed_tT.png at these times, s (e.g. 1,10,20,30,35)")
      ->delimiter(',');
  animate->add_option("--fps", an.fps, "frames per second")->capture_default_str()->check(within(0.1, 100.0));
  animate->add_option("--max-speed", an.max_speed, "m/s at the top of the colour bar (default: the fastest block)")
      ->check(within(0.0, 1e6));
  animate->add_flag("--mp4", an.mp4, "also write animation.mp4 (needs ffmpeg)");

  VerifyArgs ver;
  BenchArgs be;
  CLI::App* bench = app.add_subcommand("bench", "forward cost across block sizes; writes bench.csv and bench.png");
  bench->add_option("scene", be.scene, "region scene file (YAML) with mesh.block_size")->required();
  bench->add_option("--sizes", be.sizes, "mean block sizes, m (default: Vajont sections I-X)")->delimiter(',');
  bench->add_option("--duration", be.duration, "s of slide simulated per size")->capture_default_str();
  bench->add_option("--out", be.out, "output folder")->capture_default_str();
  bench->add_option("--set", be.sets, "override a scene value, KEY=VALUE (repeatable)");
  bench->add_option("--integrator", be.integrator, "solver: implicit, substep or auto (default: the scene's)")
      ->check(CLI::IsMember({"implicit", "substep", "auto"}));

  CLI::App* verify = app.add_subcommand("verify", "run the built-in analytic verification suite");
  verify->add_option("--only", ver.only, "run only the checks whose name contains this text");
  verify->add_option("--integrator", ver.integrator, "the solver whose suite runs: implicit, substep or all")
      ->check(CLI::IsMember({"implicit", "substep", "all"}))
      ->capture_default_str();
  verify->add_flag("--stability-map", ver.stability_map,
                   "run the incline over a grid of time steps and penalties (docs/verification.md)");

  // One thread budget for every command that runs the model (thread_budget.hpp).
  int threads = 0;
  for (CLI::App* command : {simulate, stable, invert, scan, verify, bench, advise})
    command->add_option("--threads", threads, "threads for the model (OpenMP); default: the core count")
        ->check(CLI::Range(1, 1024));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A mistyped subcommand ("simulat") reads as a missing one to CLI11; name the nearest.
    std::vector<std::string> names;
    for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
    if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end()) {
      std::cerr << "ddafit: unknown command '" << argv[1] << "'" << did_you_mean(argv[1], names)
                << "; commands: " << CLI::detail::join(names, ", ") << " (ddafit --help)\n";
      return kExitBadInput;
    }
    std::cerr << "ddafit: " << e.what() << " (ddafit --help)\n";
    return kExitBadInput;
  }
  ddafit::batch::set_thread_budget(threads);
  sc.threads = threads;
  sim.threads = threads;
  inv.threads = threads;
  ad.threads = threads;
  // Under mpirun every rank runs this; `scan` splits into a manager and workers, and the
  // guard ends MPI on every way out.
  const ddafit::batch::MpiWorld world = ddafit::batch::mpi_start(&argc, &argv);
  struct MpiGuard {
    ~MpiGuard() { ddafit::batch::mpi_stop(); }
  } mpi_guard;
  sc.mpi_rank = world.rank;
  sc.mpi_size = world.size;
  const bool ensemble = *simulate && sim.ensemble > 0;
  if (ensemble) {
    sim.mpi_rank = world.rank;
    sim.mpi_size = world.size;
  }
  if (world.size > 1 && !*scan && !ensemble) {
    // Only `scan` and `simulate --ensemble` divide their work between ranks; any other
    // command would run K copies writing the same files. Rank 0 runs it alone.
    if (world.rank > 0) return kExitSuccess;
    std::cerr << "note: only `ddafit scan` and `ddafit simulate --ensemble` use MPI ranks; rank 0 runs this "
                 "command alone\n";
  }
  // Each command reports its own errors in one line; this is the net under them, so that
  // an error nobody foresaw still ends as a message and exit 2, never as an abort.
  try {
    if (*simulate) return run_simulate(sim);
    if (*verify) return run_verify(ver);
    if (*mesh_cmd) return run_mesh(mesh);
    if (*stable) return run_stable(st);
    if (*sled) return run_sled(sl);
    if (*import_cmd) return run_import(im);
    if (*advise) return run_advise(ad);
    if (*bench) return run_bench(be);
    if (*plot) return run_plot(pl);
    if (*invert) return run_invert(inv);
    if (*scan) return run_scan(sc);
    if (*animate) return run_animate(an);
  } catch (const std::exception& e) {
    std::cerr << "ddafit " << app.get_subcommands().front()->get_name() << ": unexpected error: " << e.what()
              << " (please report it with the input that caused it)\n";
  }
  return kExitBadInput;
}
