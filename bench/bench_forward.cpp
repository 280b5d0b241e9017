// Forward-model benchmarks (Release build): `./build/bench/ddafit_bench`.
// Results and the machine are recorded in docs/performance.md.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "forward/contact/detect_contacts.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace {

using namespace ddafit;

void report(benchmark::State& state, const SimulationResult& r) {
  state.counters["steps"] = static_cast<double>(r.summary.run.steps);
  state.counters["oc_iterations"] = static_cast<double>(r.summary.run.open_close_iterations);
  state.counters["ms_per_step"] = 1e3 * r.summary.profile.total / static_cast<double>(r.summary.run.steps);
  state.counters["solve_share"] = r.summary.profile.solve / r.summary.profile.total;
  if (r.summary.status != RunStatus::Completed) state.SkipWithError(r.summary.message.c_str());
}

// The seed's incline with degradation (phi = 25, i = 5): 2 s, 2000 steps.
void BM_InclineDegradation(benchmark::State& state) {
  verification::InclineSetup setup;
  setup.roughness_angle = 5.0;
  const Scene scene = verification::incline_scene(setup);
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
}
BENCHMARK(BM_InclineDegradation)->Unit(benchmark::kMillisecond);

// A 100-brick wall (10 courses x 10) standing on a floor for 0.5 s: ~200 contacts. Arg:
// 0 implicit, 1 substep.
void BM_BrickWall100(benchmark::State& state) {
  Scene scene = verification::brick_wall_scene(10, 10, 0.5);
  scene.options.integrator = state.range(0) ? Integrator::Substep : Integrator::Implicit;
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
}
BENCHMARK(BM_BrickWall100)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// cases/walls/brick_wall_1621.yaml: 1620 bricks of 2 m x 1 m on a floor (the wall the issue
// compares with a public DDA code, 390 s per simulated second). Arg: 0 implicit (0.02 s
// simulated: a second would take minutes), 1 substep (the whole 1 s).
void BM_BrickWall1621(benchmark::State& state) {
  const bool substep = state.range(0) != 0;
  Scene scene = io::read_scene(std::string(DDAFIT_CASES_DIR) + "/walls/brick_wall_1621.yaml",
                               {{"time.integrator", substep ? "substep" : "implicit"},
                                {"time.duration", substep ? "1" : "0.02"}});
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
  state.counters["wall_per_simulated_s"] = r.summary.profile.total / r.summary.run.simulated_time;
  state.counters["top_moved_mm"] = 1e3 * r.summary.points[0].max_total_displacement;
}
BENCHMARK(BM_BrickWall1621)->Arg(1)->Arg(0)->Unit(benchmark::kSecond)->Iterations(1);

// Scaling of the same wall with size: cost per step against block count.
void BM_BrickWallScaling(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  Scene scene = verification::brick_wall_scene(side, side, 0.05);
  scene.options.integrator = state.range(1) ? Integrator::Substep : Integrator::Implicit;
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
  state.counters["blocks"] = side * side;
}
BENCHMARK(BM_BrickWallScaling)
    ->ArgsProduct({{10, 20, 40}, {0, 1}})
    ->ArgNames({"side", "substep"})
    ->Unit(benchmark::kMillisecond);

// The contact stage alone (broad and narrow phase, detect_contacts.hpp) on Vajont section VII
// as meshed at t = 0 (3136 blocks, 9 839 manifolds; about twice that in the runout): the stage the substep solver runs
// once per step, over a mass at rest, so the narrow phase's flush and proud-edge rules all
// run. Settings as run_substep.cpp sets them (slop 1e-3 of the largest move per step, the
// margin search_distance_factor times it). Repeat it (--benchmark_repetitions) and read the
// minimum: a change of a few percent in the narrow phase is lost in one run's noise. Or count
// its instructions, which a shared machine does not disturb: CGAL's meshing does not run under
// valgrind, so cut the blocks first and name the cut scene in DDAFIT_BENCH_SCENE:
//   ddafit mesh cases/vajont/degraded.yaml --out /tmp/vii
//   DDAFIT_BENCH_SCENE=/tmp/vii/scene.yaml OMP_NUM_THREADS=1 valgrind --tool=callgrind
//     build/bench/ddafit_bench --benchmark_filter=FindContacts --benchmark_min_time=0.001
// (one command, broken here).
void BM_FindContactsSectionVII(benchmark::State& state) {
  const char* cut = std::getenv("DDAFIT_BENCH_SCENE");
  const std::string path = cut ? std::string(cut) : std::string(DDAFIT_CASES_DIR) + "/vajont/degraded.yaml";
  const Scene scene = io::read_scene(path, {});
  const BlockSystem system = build_block_system(scene);
  ContactDetection detection;
  if (const std::string bad = prepare_detection(system, detection); !bad.empty()) state.SkipWithError(bad.c_str());
  const double max_move = scene.options.max_displacement_ratio * system.half_model_size;
  detection.settings.margin = scene.options.search_distance_factor * max_move;
  detection.settings.linear_slop = 1e-3 * max_move;
  detection.settings.gravity = scene.gravity;
  ContactSet contacts;
  detect_contacts(system, detection, contacts);  // the first call forms bonds; time the steady ones
  for (auto _ : state) {
    const std::string problem = detect_contacts(system, detection, contacts);
    if (!problem.empty()) state.SkipWithError(problem.c_str());
  }
  state.counters["manifolds"] = static_cast<double>(contacts.manifolds.size());
}
BENCHMARK(BM_FindContactsSectionVII)->Unit(benchmark::kMillisecond);

}  // namespace
