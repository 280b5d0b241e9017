// The forward model in one call: a scene in, the measurement history and a summary out
// (forward/run_summary.hpp). It picks the solver (time.integrator, the Auto rule) and runs it.
#pragma once

#include "forward/run_summary.hpp"
#include "forward/scene.hpp"

namespace ddafit {

SimulationResult simulate(const Scene& scene, const SimulationHooks& hooks = {});

}  // namespace ddafit
