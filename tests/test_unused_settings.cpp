// A setting that the running solver does not read is named in the run's one warning, so that a
// user who sets it learns it changed nothing (docs/scene-format.md, "Settings the running solver
// does not read"). Every key of the other solver, one at a time, on seed §2.3's incline for one
// step; and none is named when nothing is set.
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

using Setting = std::pair<std::string, std::function<void(SimulationOptions&)>>;

// Runs the incline for one 1 ms step on `integrator` with `set` applied; returns its warnings.
std::vector<std::string> warnings_of(Integrator integrator, const std::function<void(SimulationOptions&)>& set) {
  verification::InclineSetup setup;
  setup.duration = setup.time_step;
  setup.output_interval = setup.time_step;
  Scene scene = verification::incline_scene(setup);
  scene.options.integrator = integrator;
  set(scene.options);
  const SimulationResult r = simulate(scene);
  EXPECT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  return r.summary.warnings;
}

bool names(const std::vector<std::string>& warnings, const std::string& key) {
  for (const std::string& w : warnings)
    if (w.find(key) != std::string::npos && w.find("not used by the") != std::string::npos) return true;
  return false;
}

void expect_each_named(Integrator running, const std::vector<Setting>& settings) {
  for (const auto& [key, set] : settings) {
    const std::vector<std::string> w = warnings_of(running, set);
    EXPECT_TRUE(names(w, key)) << key << " set on the " << to_string(running) << " solver is not named";
  }
}

TEST(UnusedSettings, TheImplicitSolverNamesEverySubstepSetting) {
  expect_each_named(Integrator::Implicit,
                    {{"time.substeps", [](SimulationOptions& o) { o.substeps = 3; }},
                     {"control.contact_hertz", [](SimulationOptions& o) { o.contact_hertz = 30.0; }},
                     {"control.contact_damping_ratio", [](SimulationOptions& o) { o.contact_damping_ratio = 1.0; }},
                     {"control.rigid_blocks", [](SimulationOptions& o) { o.rigid_blocks = false; }},
                     {"control.contact_passes", [](SimulationOptions& o) { o.contact_passes = 4; }},
                     {"control.deep_overlap_ratio", [](SimulationOptions& o) { o.deep_overlap_ratio = 1e-3; }},
                     {"control.sleep_time", [](SimulationOptions& o) { o.sleep_time = 1.0; }},
                     {"control.sleep_speed", [](SimulationOptions& o) { o.sleep_speed = 0.01; }},
                     {"control.split_impulses", [](SimulationOptions& o) { o.split_impulses = false; }},
                     {"control.step_by_turn", [](SimulationOptions& o) { o.step_by_turn = true; }},
                     {"control.quiet_start_steps", [](SimulationOptions& o) { o.quiet_start_steps = 250; }}});
}

TEST(UnusedSettings, TheSubstepSolverNamesEveryImplicitSetting) {
  expect_each_named(Integrator::Substep,
                    {{"control.max_open_close_iterations",
                      [](SimulationOptions& o) { o.max_open_close_iterations = 12; }},
                     {"control.reuse_factorization", [](SimulationOptions& o) { o.reuse_factorization = true; }},
                     {"control.update_factorization", [](SimulationOptions& o) { o.update_factorization = false; }},
                     {"control.settle_passes", [](SimulationOptions& o) { o.settle_passes = 10; }},
                     {"control.max_penetration_ratio", [](SimulationOptions& o) { o.max_penetration_ratio = 1e-4; }},
                     {"control.contact_tolerance_ratio",
                      [](SimulationOptions& o) { o.contact_tolerance_ratio = 1e-6; }},
                     {"control.penalty", [](SimulationOptions& o) { o.penalty = 1e9; }},
                     {"control.penalty_factor", [](SimulationOptions& o) { o.penalty_factor = 20.0; }},
                     {"control.shear_penalty_ratio", [](SimulationOptions& o) { o.shear_penalty_ratio = 0.5; }},
                     // Named since 2026-12-07: the table of docs/scene-format.md had them as the
                     // implicit solver's, and a substep run took them without a word.
                     {"control.step_cut_factor", [](SimulationOptions& o) { o.step_cut_factor = 0.5; }},
                     {"control.penalty_raise_factor", [](SimulationOptions& o) { o.penalty_raise_factor = 2.0; }},
                     {"control.max_penalty_raises", [](SimulationOptions& o) { o.max_penalty_raises = 3; }}});
}

TEST(UnusedSettings, NothingSetNothingNamed) {
  for (const Integrator running : {Integrator::Implicit, Integrator::Substep})
    for (const std::string& w : warnings_of(running, [](SimulationOptions&) {}))
      EXPECT_EQ(w.find("not used by the"), std::string::npos) << to_string(running) << ": " << w;
}

}  // namespace
}  // namespace ddafit
