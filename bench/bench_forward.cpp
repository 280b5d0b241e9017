// Forward-model benchmarks (Release build): `./build/bench/ddafit_bench`.
// Results and the machine are recorded in docs/performance.md.
#include <benchmark/benchmark.h>

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

// A 100-brick wall (10 courses x 10) standing on a floor for 0.5 s: ~200 contacts.
void BM_BrickWall100(benchmark::State& state) {
  const Scene scene = verification::brick_wall_scene(10, 10, 0.5);
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
}
BENCHMARK(BM_BrickWall100)->Unit(benchmark::kMillisecond);

// Scaling of the same wall with size: cost per step against block count.
void BM_BrickWallScaling(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const Scene scene = verification::brick_wall_scene(side, side, 0.05);
  SimulationResult r;
  for (auto _ : state) r = simulate(scene);
  report(state, r);
  state.counters["blocks"] = side * side;
}
BENCHMARK(BM_BrickWallScaling)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

}  // namespace
