#include "forward/step/run_implicit.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/sparse_system.hpp"
#include "forward/step/control_time_step.hpp"
#include "forward/common/containment_check.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/earthquake/ground_motion.hpp"
#include "forward/step/new_points.hpp"
#include "forward/step/implicit_context.hpp"
#include "forward/step/judge_step.hpp"
#include "forward/step/open_close_iterate.hpp"
#include "forward/step/settle_contacts.hpp"
#include "forward/step/resolve_impacts.hpp"
#include "forward/step/update_blocks.hpp"

namespace ddafit {
namespace {

// Settling may move a block by up to this many steps' worth of displacement: enough for
// the elastic shortening of a tall mass, not for a block that is falling over.
constexpr double kSettleShiftSteps = 10.0;

// The deepest overlap at the end of an accepted step (the points' gaps from the step's
// unknowns), relative to the smaller free block of its pair.
void measure_overlaps(const BlockSystem& s, const ContactSet& contacts, double time, WorstOverlap& worst) {
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].spring.state != ContactState::Open) worst.note(s, m, -m.points[q].spring.normal_gap, time);
}

}  // namespace

double automatic_penalty(const Scene& scene) {
  if (scene.options.penalty > 0.0) return scene.options.penalty;
  double largest = 0.0;
  for (const Material& m : scene.materials) largest = std::max(largest, m.young_modulus);
  return scene.options.penalty_factor * largest;
}

void run_implicit(const Scene& scene, BlockSystem& system, RunRecorder& recorder, SimulationSummary& summary) {
  const SimulationOptions& options = scene.options;
  SolverOptions solver_options;
  solver_options.reuse_factorization = options.reuse_factorization;
  solver_options.update_factorization = options.update_factorization;
  ImplicitStepContext ctx(scene, system, summary, solver_options);
  TimeStepControl& control = ctx.control;
  double heaviest_weight = 0.0;  // m |g| of the heaviest free block (control_time_step.hpp)
  for (int b = 0; b < static_cast<int>(system.blocks.size()); ++b)
    if (!system.blocks[b].fixed) heaviest_weight = std::max(heaviest_weight, system.mass(b) * scene.gravity.norm());
  control = make_time_step_control(options, scene.max_step, system.half_model_size,
                                   step_move_limit(options.max_displacement_ratio, system), automatic_penalty(scene),
                                   heaviest_weight);
  CollideSettings& settings = ctx.detection.settings;
  set_run_tolerances(settings, options.search_distance_factor, control.max_displacement);
  settings.first_step = true;
  settings.gravity = scene.gravity;
  if (const std::string bad = prepare_detection(system, ctx.detection); !bad.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "block '" + bad + "': its polygon could not be split into convex pieces for contact";
    return;
  }
  prepare_shear_bands(system, scene.duration, ctx.contacts);

  const GroundTrack ground(scene.earthquake);
  double time = 0.0;
  // The springs and loads of one attempt at a step of length dt from `time`.
  const auto step_parameters = [&](double dt) {
    StepParameters p{dt, control.penalty, options.shear_penalty_ratio * control.penalty, scene.gravity,
                     control.contact_tolerance, options.max_pushout_speed * dt};
    p.ground_acceleration = ground.mean_acceleration(time, time + dt);
    return p;
  };
  StepProfile& profile = ctx.profile;
  RunCounters& run = ctx.run;
  run.smallest_step = scene.max_step;

  if (options.settle_passes > 0) {
    // The contacts touching at t = 0 start loaded (forward/step/settle_contacts.hpp).
    std::string problem;
    {
      ScopedTimer timer(profile.find_contacts);
      settings.first_step = true;
      problem = detect_contacts(system, ctx.detection, ctx.contacts);
    }
    ScopedTimer timer(profile.settle);
    StepParameters step = step_parameters(control.step);
    step.ground_acceleration.setZero();  // before the clock runs: the ground is still
    const bool settled =
        problem.empty() && settle_contacts(ctx, step, kSettleShiftSteps * control.max_displacement, problem);
    if (!problem.empty()) {
      summary.status = RunStatus::InvalidScene;
      summary.message = "t = 0: " + problem;
      return;
    }
    if (!settled) {
      summary.status = RunStatus::Failed;
      summary.message = "t = 0: the initial contact settling could not be solved: check for blocks that "
                        "overlap or a penalty far stiffer than the blocks";
      return;
    }
    settings.first_step = false;  // bonds formed between the blocks touching once settled
  }

  recorder.start(system);
  EnergyAudit audit = start_energy_audit(system, scene.gravity);

  auto fail = [&](RunStatus status, const std::string& why) {
    std::ostringstream out;
    out << "t = " << time << " s, step " << run.steps + 1 << ": " << why;
    summary.status = status;
    summary.message = out.str();
  };

  std::vector<char> struck;  // per block: in an impact this step (resolve_impacts refills it)
  StepStart step_start;  // the centroids before the step, for the containment check
  while (!recorder.finished(time) && !recorder.interrupted(time, system)) {
    remember_step_start(system, step_start);
    {
      ScopedTimer timer(profile.find_contacts);
      settings.slip_step = control.step;
      const std::string problem = detect_contacts(system, ctx.detection, ctx.contacts);
      if (!problem.empty()) {
        fail(RunStatus::InvalidScene, problem);
        break;
      }
      start_new_points(system, ctx.contacts, control.step, control.contact_tolerance);
    }
    {
      ScopedTimer timer(profile.update);
      if (resolve_impacts(ctx, control.step, struck) > 0)
        start_impact_slides(system, ctx.contacts, struck, control.step,
                            control.contact_tolerance,
                            options.shear_penalty_ratio * control.penalty);
    }
    ctx.saved = ctx.contacts;
    bool accepted = false;
    double attempt = 0.0;
    double landing = -1.0;  // the output time or end time this step lands on exactly, if any
    while (!accepted) {
      attempt = recorder.fit_step(time, control.step, &landing);
      if (attempt != settings.slip_step) predict_first_slip(system, ctx.contacts, attempt);
      const StepParameters step = step_parameters(attempt);
      const OpenCloseResult oc = open_close_iterate(ctx, step);
      run.open_close_iterations += oc.iterations;
      run.unsettled_contacts += oc.unsettled;
      const StepJudgement judgement = judge_step(ctx, step, oc);
      if (judgement.verdict == StepVerdict::Accept) {
        accepted = true;
        break;
      }
      ctx.contacts = ctx.saved;
      if (judgement.verdict == StepVerdict::Stiffer) continue;
      ++run.step_cuts;
      control.step = attempt;
      if (!cut_step(control, judgement.cut_factor)) {
        fail(RunStatus::Failed, judgement.why + "; the time step fell below " + std::to_string(control.min_step) +
                                    " s. Try a smaller time.step or control.max_displacement_ratio, a different "
                                    "control.penalty, or a larger control.max_open_close_iterations");
        break;
      }
    }
    if (!accepted) break;

    {
      ScopedTimer timer(profile.update);
      if (ground.present()) {  // the load -m a_g over the centroids' moves, D's translation
        Vec2 moved = Vec2::Zero();
        for (int b = 0; b < static_cast<int>(system.blocks.size()); ++b)
          if (system.blocks[b].unknown >= 0)
            moved += audit.mass[b] * ctx.equations.d.segment<2>(6 * system.blocks[b].unknown);
        add_load_work(audit, ground.mean_acceleration(time, time + attempt), moved);
      }
      update_blocks(ctx, attempt);
    }
    time = landing >= 0.0 ? landing : time + attempt;
    measure_overlaps(system, ctx.contacts, time, ctx.worst);
    ++run.steps;
    run.smallest_step = std::min(run.smallest_step, attempt);
    run.largest_step = std::max(run.largest_step, attempt);
    grow_step(control, options);
    if (const std::string problem = check_energy(audit, system, scene.gravity); !problem.empty()) {
      recorder.record_row(time, system);
      fail(RunStatus::Failed, problem);
      break;
    }
    if (const std::string problem = check_containment(system, &step_start); !problem.empty()) {
      recorder.record_row(time, system);
      fail(RunStatus::Failed, problem);
      break;
    }
    recorder.record(time, system);
  }
  run.simulated_time = time;
  run.symbolic_analyses = ctx.solver.counters().symbolic_analyses;
  run.factorizations = ctx.solver.counters().factorizations;
  run.cg_solves = ctx.solver.counters().cg_solves;
  run.factor_updates = ctx.solver.counters().factor_updates;
  run.update_rank = ctx.solver.counters().update_rank;
  run.final_penalty = control.penalty;
  report_overlap(system, ctx.worst, summary.solver);
}

}  // namespace ddafit
