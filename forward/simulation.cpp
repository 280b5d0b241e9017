// simulate(): check the scene, build the blocks, pick the solver and run it. The two
// solvers share the scene, the block system, the contact stage and law (forward/contact/),
// the energy audit and the recording of the run (forward/run_record.hpp).
#include "forward/simulation.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "forward/common/known_limits.hpp"
#include "forward/perturb.hpp"
#include "forward/run_record.hpp"
#include "forward/step/run_implicit.hpp"
#include "forward/sled/sled.hpp"
#include "forward/substep/run_substep.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ddafit {
namespace {

// The shortest time step, as a fraction of the elastic period L / c of the largest free block
// (c = sqrt(E / rho)), at which the implicit solver's accuracy has been checked: sliders of 10-200 m
// from rest (scripts/landslide_block_steps.py, tests/test_landslide_blocks.cpp) within 0.11 % of
// seed Eq. 4 down to 3e-4 L/c, and the seed's incline down to 0.003 L/c (docs/verification.md,
// "Stability map"). Below it a run is outside what was checked, and is warned. Until model
// revision 2026-12-06.6 the warning came at 0.01 L/c (0.1 before .06.3): sliders of landslide size
// then ran up to 78 % off at 0.005 L/c, because a resting point's spring could hold no more than
// the penalty times max_pushout_speed x dt (forward/step/assemble.hpp, spring_reference) and the
// settling passes read a slow approach as a fall (forward/step/settle_contacts.hpp).
constexpr double kElasticPeriodFraction = 3e-4;

std::string time_step_warning(const Scene& scene, const BlockSystem& s) {
  int which = -1;
  const double longest = longest_elastic_period(scene, s, &which);
  if (which < 0 || scene.max_step >= kElasticPeriodFraction * longest) return {};
  std::ostringstream out;
  out << "time.step " << scene.max_step << " s is below " << kElasticPeriodFraction
      << " x the elastic period of block '" << s.block_names[which] << "' (" << longest
      << " s), shorter than any step the implicit solver's accuracy was checked at (sliders of 10-200 m from rest "
         "within 0.11 % of seed Eq. 4 down to 0.0003 x; docs/theory.md, known limits (a)); use time.step >= "
      << kElasticPeriodFraction * longest << " s";
  return out.str();
}

// The implicit solver's known limit (i) (docs/theory.md): a tall block sliding, from rest or given
// a velocity along its face.
std::string tall_slider_warning(const BlockSystem& s, const TallSlider& slider) {
  std::ostringstream out;
  out.precision(3);
  out << "block '" << s.block_names[slider.block] << (slider.launched ? "' is given a velocity along" : "' slides from rest on")
      << " a face " << slider.slope << " deg steep (friction " << slider.friction
      << " deg) with its base reaction at r = tan(phi) H / L = "
      << slider.reach << " of its half-length ahead of its centre: the implicit solver takes such tall sliders "
         "up to 70 % off seed Eq. 4 where they cross joints (docs/theory.md, known limits (i)); "
         "time.integrator: substep keeps them within 1e-3";
  return out.str();
}

// Known limit (j): a block resting on a free block much lighter than itself.
std::string heavy_on_light_warning(const BlockSystem& s, const HeavyOnLight& heavy) {
  std::ostringstream out;
  out.precision(3);
  out << "block '" << s.block_names[heavy.heavy] << "' rests on block '" << s.block_names[heavy.light] << "', "
      << heavy.ratio << " times lighter: heavy blocks sliding on blocks " << kHeavyOnLightRatio
      << " or more times lighter run off seed Eq. 4 on both solvers, and more often and far more slowly on the "
         "implicit one (docs/theory.md, known limits (j)); time.integrator: substep is the better of the two there";
  return out.str();
}

// Integrator::Auto's rule (options.hpp, kAutoSubstepBlocks), and the reason given in
// the summary.
SolverReport choose_solver(const Scene& scene, const BlockSystem& s, const KnownLimits& limits) {
  const TallSlider& slider = limits.slider;
  SolverReport report;
  if (scene.options.integrator != Integrator::Auto) {
    report.integrator = scene.options.integrator;
    report.reason = std::string("time.integrator: ") + to_string(scene.options.integrator);
    return report;
  }
  const bool many = s.free_block_count >= kAutoSubstepBlocks;
  report.integrator = many ? Integrator::Substep : Integrator::Implicit;
  report.reason = "auto: " + std::to_string(s.free_block_count) + " free blocks, " + (many ? ">= " : "< ") +
                  std::to_string(kAutoSubstepBlocks) + " (docs/speed-accuracy.md)";
  if (many) return report;
  // Not the implicit solver for a scene of its known limits (i) and (j) (the warnings above).
  std::ostringstream why;
  why.precision(3);
  if (is_tall(slider)) {
    why << ", but block '" << s.block_names[slider.block] << "' is a tall slider (r = tan(phi) H / L = " << slider.reach
        << "), which the implicit solver runs off seed Eq. 4 (docs/theory.md, known limits (i))";
  } else if (const HeavyOnLight& heavy = limits.heavy; is_heavy_on_light(heavy)) {
    why << ", but block '" << s.block_names[heavy.heavy] << "' rests on block '" << s.block_names[heavy.light] << "', "
        << heavy.ratio << " times lighter, which the implicit solver runs off seed Eq. 4 more often than the substep "
           "solver (docs/theory.md, known limits (j))";
  } else {
    return report;
  }
  report.integrator = Integrator::Substep;
  report.reason += why.str();
  return report;
}

// Settings that only one solver reads, set away from their defaults under the other:
// said, never silently ignored.
// Under time.integrator: auto a scene may carry both solvers' settings on purpose (the
// Vajont scenes run either way with mesh.block_size); the message then says why these
// are not used here rather than suggesting a mistake.
std::vector<std::string> unused_setting_warnings(const SimulationOptions& o, const SolverReport& solver) {
  const Integrator running = solver.integrator;
  if (running == Integrator::Sled) return {};  // the sled reads no contact setting of either solver
  const SimulationOptions d;
  std::vector<std::string> unused;
  if (running == Integrator::Substep) {
    if (o.max_open_close_iterations != d.max_open_close_iterations) unused.push_back("control.max_open_close_iterations");
    if (o.reuse_factorization != d.reuse_factorization) unused.push_back("control.reuse_factorization");
    if (o.update_factorization != d.update_factorization) unused.push_back("control.update_factorization");
    if (o.settle_passes != d.settle_passes) unused.push_back("control.settle_passes");
    if (o.penalty != d.penalty) unused.push_back("control.penalty");
    if (o.penalty_factor != d.penalty_factor) unused.push_back("control.penalty_factor");
    if (o.shear_penalty_ratio != d.shear_penalty_ratio) unused.push_back("control.shear_penalty_ratio");
    if (o.max_penetration_ratio != d.max_penetration_ratio) unused.push_back("control.max_penetration_ratio");
    if (o.contact_tolerance_ratio != d.contact_tolerance_ratio) unused.push_back("control.contact_tolerance_ratio");
    if (o.step_cut_factor != d.step_cut_factor) unused.push_back("control.step_cut_factor");
    if (o.penalty_raise_factor != d.penalty_raise_factor) unused.push_back("control.penalty_raise_factor");
    if (o.max_penalty_raises != d.max_penalty_raises) unused.push_back("control.max_penalty_raises");
  } else {
    if (o.substeps != d.substeps) unused.push_back("time.substeps");
    if (o.contact_hertz != d.contact_hertz) unused.push_back("control.contact_hertz");
    if (o.contact_damping_ratio != d.contact_damping_ratio) unused.push_back("control.contact_damping_ratio");
    if (o.rigid_blocks != d.rigid_blocks) unused.push_back("control.rigid_blocks");
    if (o.contact_passes != d.contact_passes) unused.push_back("control.contact_passes");
    if (o.deep_overlap_ratio != d.deep_overlap_ratio) unused.push_back("control.deep_overlap_ratio");
    if (o.sleep_time != d.sleep_time) unused.push_back("control.sleep_time");
    if (o.sleep_speed != d.sleep_speed) unused.push_back("control.sleep_speed");
    if (o.split_impulses != d.split_impulses) unused.push_back("control.split_impulses");
    if (o.step_by_turn != d.step_by_turn) unused.push_back("control.step_by_turn");
    if (o.quiet_start_steps != d.quiet_start_steps) unused.push_back("control.quiet_start_steps");
  }
  if (unused.empty()) return {};
  std::string list;
  for (const std::string& key : unused) list += (list.empty() ? "" : ", ") + key;
  if (o.integrator == Integrator::Auto)
    return {list + (unused.size() == 1 ? " is a setting" : " are settings") + " of the other solver, kept for when "
            "time.integrator: auto picks it; here it picked the " + to_string(running) + " solver (" + solver.reason +
            "), so " + (unused.size() == 1 ? "it is" : "they are") + " not used"};
  return {list + (unused.size() == 1 ? " is" : " are") + " not used by the " + to_string(running) +
          " solver (docs/scene-format.md)"};
}

}  // namespace

SimulationResult simulate(const Scene& given, const SimulationHooks& hooks) {
  const auto wall_start = std::chrono::steady_clock::now();
  SimulationResult result;
  SimulationSummary& summary = result.summary;
  if (const auto errors = validate_scene(given); !errors.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = errors.front().key + ": " + errors.front().problem;
    return result;
  }
  // An ensemble member starts from the checked scene, nudged (forward/perturb.hpp).
  const Scene nudged = given.options.realisation > 0 ? perturbed_scene(given, given.options.realisation) : Scene();
  const Scene& scene = given.options.realisation > 0 ? nudged : given;
#ifdef _OPENMP
  if (scene.options.threads > 0) omp_set_num_threads(scene.options.threads);
#endif

  BlockSystem system = build_block_system(scene);
  // The known limits' classes, wherever the implicit solver may run (choose_solver and the
  // warnings above).
  const Integrator asked = scene.options.integrator;
  const bool implicit_possible = asked == Integrator::Implicit ||
                                 (asked == Integrator::Auto && system.free_block_count < kAutoSubstepBlocks);
  const KnownLimits limits = implicit_possible ? find_known_limits(scene, system) : KnownLimits{};
  summary.solver = choose_solver(scene, system, limits);
  for (std::string& w : unused_setting_warnings(scene.options, summary.solver))
    summary.warnings.push_back(std::move(w));
  RunRecorder recorder(scene, hooks, result);
  if (summary.solver.integrator == Integrator::Sled) {
    result.sled = run_sled(scene, system, recorder, summary);
  } else if (summary.solver.integrator == Integrator::Substep) {
    run_substep(scene, system, recorder, summary);
  } else {
    if (std::string w = time_step_warning(scene, system); !w.empty()) summary.warnings.push_back(w);
    if (is_tall(limits.slider)) summary.warnings.push_back(tall_slider_warning(system, limits.slider));
    if (is_heavy_on_light(limits.heavy)) summary.warnings.push_back(heavy_on_light_warning(system, limits.heavy));
    run_implicit(scene, system, recorder, summary);
  }
  if (summary.status == RunStatus::Completed)
    if (std::string w = overlap_warning(scene, summary.solver); !w.empty()) summary.warnings.push_back(std::move(w));
  summary.profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace ddafit
