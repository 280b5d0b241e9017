#include "forward/step/run_implicit.hpp"

#include <algorithm>
#include <sstream>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/sparse_system.hpp"
#include "forward/step/control_time_step.hpp"
#include "forward/common/containment_check.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/step/new_points.hpp"
#include "forward/step/open_close_iterate.hpp"
#include "forward/step/settle_contacts.hpp"
#include "forward/step/update_blocks.hpp"

namespace ddafit {
namespace {

// Settling may move a block by up to this many steps' worth of displacement: enough for
// the elastic shortening of a tall mass, not for a block that is falling over.
constexpr double kSettleShiftSteps = 10.0;

// Overlap tolerated without changing a contact's state, as a fraction of the largest
// displacement allowed per step (the separating-axis tolerance of the manifold).
constexpr double kSlopRatio = 1e-3;

std::string describe_contact(const BlockSystem& s, const ContactSet& contacts, PointRef at) {
  const ContactManifold& m = contacts.manifolds[at.manifold];
  const ContactPoint& p = m.points[at.point];
  std::ostringstream out;
  out << "contact of blocks '" << s.block_names[m.block_a] << "' and '" << s.block_names[m.block_b] << "' at ("
      << p.anchor.x() << ", " << p.anchor.y() << ") (" << to_string(p.spring.state) << ", gap " << p.spring.normal_gap
      << " m)";
  return out.str();
}

// The deepest overlap at the end of an accepted step (the points' gaps from the step's
// unknowns), relative to the smaller free block of its pair.
void measure_overlaps(const BlockSystem& s, const ContactSet& contacts, double time, WorstOverlap& worst) {
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].spring.state != ContactState::Open) note_overlap(s, m, -m.points[q].spring.normal_gap, time, worst);
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
  TimeStepControl control =
      make_time_step_control(options, scene.max_step, system.half_model_size, automatic_penalty(scene));
  ContactDetection detection;
  detection.settings.margin = options.search_distance_factor * control.max_displacement;
  detection.settings.linear_slop = kSlopRatio * control.max_displacement;
  detection.settings.first_step = true;
  detection.settings.gravity = scene.gravity;
  if (const std::string bad = prepare_detection(system, detection); !bad.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "block '" + bad + "': its polygon could not be split into convex pieces for contact";
    return;
  }

  // The springs and loads of one attempt at a step of length dt.
  const auto step_parameters = [&](double dt) {
    return StepParameters{dt, control.penalty, options.shear_penalty_ratio * control.penalty, scene.gravity,
                          options.contact_tolerance_ratio * control.max_displacement,
                          options.max_pushout_speed * dt};
  };
  ContactSet contacts, saved;
  WorstOverlap worst;
  BlockSparseMatrix k;
  Eigen::VectorXd f, d;
  SolverOptions solver_options;
  solver_options.reuse_factorization = options.reuse_factorization;
  SparseSolver solver(solver_options);
  StepProfile& profile = summary.profile;
  RunCounters& run = summary.run;
  run.smallest_step = scene.max_step;
  double time = 0.0;

  if (options.settle_passes > 0) {
    // The contacts touching at t = 0 start loaded (forward/step/settle_contacts.hpp).
    std::string problem;
    {
      ScopedTimer timer(profile.find_contacts);
      detection.settings.first_step = true;
      problem = detect_contacts(system, detection, contacts);
    }
    ScopedTimer timer(profile.settle);
    const StepParameters step = step_parameters(control.step);
    const bool settled = problem.empty() && settle_contacts(system, detection, contacts, step, options.settle_passes,
                                                            kSettleShiftSteps * control.max_displacement, solver, problem);
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
    detection.settings.first_step = false;  // bonds formed between the blocks touching once settled
  }

  recorder.start(system);
  const EnergyAudit audit = start_energy_audit(system, scene.gravity);

  auto fail = [&](RunStatus status, const std::string& why) {
    std::ostringstream out;
    out << "t = " << time << " s, step " << run.steps + 1 << ": " << why;
    summary.status = status;
    summary.message = out.str();
  };

  while (!recorder.finished(time) && !recorder.interrupted(time, system)) {
    {
      ScopedTimer timer(profile.find_contacts);
      const std::string problem = detect_contacts(system, detection, contacts);
      if (!problem.empty()) {
        fail(RunStatus::InvalidScene, problem);
        break;
      }
      start_new_points(system, contacts, control.step, options.contact_tolerance_ratio * control.max_displacement);
    }
    saved = contacts;
    bool accepted = false;
    double attempt = 0.0;
    double landing = -1.0;  // the output time or end time this step lands on exactly, if any
    while (!accepted) {
      attempt = recorder.fit_step(time, control.step, &landing);
      const StepParameters step = step_parameters(attempt);
      const OpenCloseResult oc =
          open_close_iterate(system, contacts, step, options, solver, k, f, d, profile);
      run.open_close_iterations += oc.iterations;
      run.unsettled_contacts += oc.unsettled;
      std::string why;
      double factor = options.step_cut_factor;
      if (!oc.converged) {
        why = oc.reason;
        if (oc.unsettled_contact.manifold >= 0) why += " at the " + describe_contact(system, contacts, oc.unsettled_contact);
      } else if (const double moved = max_vertex_displacement(system, d); moved > control.max_displacement) {
        why = "a vertex moved " + std::to_string(moved) + " m in one step (limit " +
              std::to_string(control.max_displacement) + " m)";
        factor = std::clamp(0.8 * control.max_displacement / moved, 0.1, 0.9);
      } else {
        PointRef deepest;
        // Half the search distance: deeper, a contact is close to being lost altogether.
        const double depth =
            max_penetration(contacts, step, control.max_penetration, 0.5 * detection.settings.margin, &deepest);
        if (depth > control.max_penetration) {
          const std::string where = describe_contact(system, contacts, deepest);
          if (raise_penalty(control, options)) {
            contacts = saved;
            ++run.penalty_raises;
            continue;
          }
          // A stiffer spring did not help: a corner running into a corner is caught
          // earlier by a shorter step. Only when the step can no longer shrink does the
          // run stop.
          why = "penetration " + std::to_string(depth) + " m at the " + where + " stays above the limit after " +
                std::to_string(control.penalty_raises) + " penalty raises in this step";
          control.penalty_raises = 0;
        } else {
          accepted = true;
          break;
        }
      }
      contacts = saved;
      ++run.step_cuts;
      control.step = attempt;
      if (!cut_step(control, factor)) {
        fail(RunStatus::Failed, why + "; the time step fell below " + std::to_string(control.min_step) +
                                    " s. Try a smaller time.step or control.max_displacement_ratio, a different "
                                    "control.penalty, or a larger control.max_open_close_iterations");
        break;
      }
    }
    if (!accepted) break;

    {
      ScopedTimer timer(profile.update);
      update_blocks(system, contacts, d, attempt, options.shear_penalty_ratio * control.penalty);
    }
    time = landing >= 0.0 ? landing : time + attempt;
    measure_overlaps(system, contacts, time, worst);
    ++run.steps;
    run.smallest_step = std::min(run.smallest_step, attempt);
    run.largest_step = std::max(run.largest_step, attempt);
    grow_step(control, options);
    if (const std::string problem = check_energy(audit, system, scene.gravity); !problem.empty()) {
      recorder.record_row(time, system);
      fail(RunStatus::Failed, problem);
      break;
    }
    if (const std::string problem = check_containment(system); !problem.empty()) {
      recorder.record_row(time, system);
      fail(RunStatus::Failed, problem);
      break;
    }
    recorder.record(time, system);
  }
  run.simulated_time = time;
  run.symbolic_analyses = solver.counters().symbolic_analyses;
  run.factorizations = solver.counters().factorizations;
  run.cg_solves = solver.counters().cg_solves;
  run.final_penalty = control.penalty;
  report_overlap(system, worst, summary.solver);
}

}  // namespace ddafit
