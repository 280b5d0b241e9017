// Forward-model benchmarks (Release build): `./build/bench/ddafit_bench`.
// Results and the machine are recorded in docs/performance.md.
#include <benchmark/benchmark.h>

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

}  // namespace
