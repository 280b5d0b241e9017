// The subcommands of the ddafit command line. Each returns the process exit code.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "apps/ddafit/plots.hpp"
#include "forward/analysis/stable_friction.hpp"
#include "forward/scene.hpp"

namespace ddafit::inverse {
struct Study;
}

namespace ddafit::app {

// Reads a study and checks it against its scene; on failure prints the one-line error.
bool load_study(const std::string& path, inverse::Study& study);

// "KEY=VALUE" scene overrides from --set, split into pairs; returns false on a bad one.
bool parse_overrides(const std::vector<std::string>& sets, std::vector<std::pair<std::string, std::string>>& out);

// Reads a scene with --set overrides; on failure prints the one-line error and
// returns false (exit code 2).
bool load_scene(const std::string& path, const std::vector<std::string>& sets, Scene& scene);

struct SimulateArgs {
  std::string scene;
  std::vector<std::string> sets;  // --set KEY=VALUE
  std::string out = "ddafit-out";
  bool quiet = false;
  double vtk_interval = 0.0;  // s between VTK snapshots; 0 = none
  bool plots = false;         // PNG charts of the history
  bool mirror = false;        // run the mirror image (forward/mirror.hpp), results read back unmirrored
  int ensemble = 0;           // > 0: run this many realisations (forward/perturb.hpp) and their spread
  int jobs = 1;               // --ensemble: realisations at a time
  double jitter = 0.0;        // --ensemble: largest nudge / block size; 0 = kJitterRatio
  bool resume = false;        // --ensemble: reuse the realisations cached in the output folder
  double run_timeout = 3600.0;  // s; --ensemble under mpirun: a run past this is killed (and retried once)
  int threads = 0;            // the command's --threads (0 = the core count)
  int mpi_rank = 0, mpi_size = 1;  // --ensemble under mpirun: this process's rank and the world's size
  std::string slurm_dir;    // --ensemble --slurm: write a job array here instead of running
  int array_limit = 4;      // --slurm: tasks at a time
  std::string collect_dir;  // --ensemble --collect: load a job array's results into the cache, then write
  std::string task_dir;     // --task (set by job.sh): run one realisation of DIR/points.txt
  long task_index = -1;     // --task-index
};
int run_simulate(const SimulateArgs& args);
// simulate --ensemble: the scene is loaded and the output folder ready (ensemble_command.cpp).
int run_ensemble_command(const SimulateArgs& args, const Scene& scene, const std::string& label);

struct MeshArgs {
  std::string scene;
  std::string out = "ddafit-mesh";
  std::vector<std::string> sets;
};
int run_mesh(const MeshArgs& args);

struct PlotArgs {
  std::string scene;
  std::string dir;
  std::vector<std::string> sets;
  ObservedRanges observed;  // an estimate drawn on the lateral speed-distance chart
};
int run_plot(const PlotArgs& args);

struct StableArgs {
  std::string scene;
  std::string interface;
  std::string out = "ddafit-stable";
  std::vector<std::string> sets;
  StableSearchOptions options;
};
int run_stable(const StableArgs& args);

struct SledArgs {
  std::string scene;
  std::string out = "ddafit-sled";
  std::vector<std::string> sets;
};
int run_sled(const SledArgs& args);

struct ImportArgs {
  std::string geometry;  // FILE.geo (DDAML)
  std::string analysis;  // FILE.ana, optional
  std::string units;     // "kN" or "SI", required
  std::string out;       // the scene file written
};
int run_import(const ImportArgs& args);

struct AdviseArgs {
  std::string scene;
  std::string quantity = "max_lateral_displacement";
  std::string point;
  std::vector<double> sizes;  // m; empty: 4, 2 and 1 x the scene's mesh.block_size
  double tolerance = 0.05;
  int members = 3;            // realisations per size, for the spread
  int jobs = 1;
  int threads = 0;
  std::string out = "ddafit-advise";
  std::vector<std::string> sets;
};
int run_advise(const AdviseArgs& args);

struct InvertArgs {
  int jobs = 1;     // forward runs at a time where they are independent (the profile's grid)
  int threads = 0;  // per run (the --threads budget)
  std::string study;
  std::string out = "ddafit-invert";
  bool resume = false;  // reuse OUT/evaluations.sqlite
  int budget = 0;       // objective calls per fit; 0 = the study's method.budget
  bool quiet = false;
  bool check = false;   // read and check the study and its scene, print the plan, run nothing
};
int run_invert(const InvertArgs& args);

struct ScanArgs {
  std::string study;
  std::string design = "profile";  // profile | grid | lhs | morris
  std::string parameter;  // profile: a continuous parameter's name in the study
  int points = 11;        // profile: points from lower to upper; grid: values per parameter
  int samples = 20;       // lhs
  int trajectories = 10;  // morris
  int levels = 4;         // morris
  long seed = 1;          // lhs, morris
  int jobs = 1;           // forward runs at a time
  int threads = 0;        // per run; 0 = the core count / jobs
  bool dry_run = false;
  double run_timeout = 3600.0;  // s; under mpirun a run past this is killed (and retried once)
  int mpi_rank = 0, mpi_size = 1;  // under mpirun: this process's rank and the world's size
  std::string slurm_dir;    // --slurm: write a job array here instead of running
  int array_limit = 4;      // --slurm: tasks at a time (sbatch --array=...%K)
  std::string collect_dir;  // --collect: load a job array's results into the cache, then report
  std::string task_dir;     // --task (set by job.sh): run one point of DIR/points.txt
  long task_index = -1;     // --task-index
  std::string out = "ddafit-scan";
  bool resume = false;
};
int run_scan(const ScanArgs& args);

struct AnimateArgs {
  std::string dir;               // a run's output folder with vtk/blocks_NNNNN.vtk
  std::string out;               // default DIR/animation
  std::vector<double> times;     // s: also write speed_tXXX.Xs.png at the snapshots nearest these
  double fps = 10.0;             // frames per second of the GIF and MP4
  double max_speed = 0.0;        // m/s, top of the colour bar; 0 = the run's fastest block
  bool mp4 = false;              // also animation.mp4 through ffmpeg
};
int run_animate(const AnimateArgs& args);

struct BenchArgs {
  std::string scene;
  // Mean block sizes, m: the seed's Vajont sections I-X by default.
  std::vector<double> sizes = {34.3, 23.1, 16.0, 12.1, 9.8, 8.9, 8.2, 7.4, 6.6, 5.7};
  double duration = 1.0;  // s of slide simulated per size
  std::string out = "ddafit-bench";
  std::vector<std::string> sets;
  std::string integrator;  // implicit | substep | auto; empty = the scene's
};
int run_bench(const BenchArgs& args);

struct VerifyArgs {
  std::string only;  // run only checks whose name contains this
  bool stability_map = false;  // print the incline stability map instead
  std::string integrator = "implicit";  // implicit | substep | all
};
int run_verify(const VerifyArgs& args);

}  // namespace ddafit::app
