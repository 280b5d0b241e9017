// The time-stepping loop: each step runs the stages of forward/step/ in order
// (find contacts -> open-close iteration [assemble, solve, check contacts] ->
// control the step -> update blocks) and records the measurement points.
#include "forward/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "forward/sparse_system.hpp"
#include "forward/step/control_time_step.hpp"
#include "forward/step/energy_check.hpp"
#include "forward/step/find_contacts.hpp"
#include "forward/step/open_close_iterate.hpp"
#include "forward/step/settle_contacts.hpp"
#include "forward/step/update_blocks.hpp"

namespace ddafit {
namespace {

double automatic_penalty(const Scene& scene) {
  if (scene.options.penalty > 0.0) return scene.options.penalty;
  double largest = 0.0;
  for (const Material& m : scene.materials) largest = std::max(largest, m.young_modulus);
  return scene.options.penalty_factor * largest;
}

Vec2 point_velocity(const BlockSystem& s, const MaterialPoint& p) {
  const Block& b = s.blocks[p.block];
  if (b.unknown < 0) return Vec2::Zero();
  return displacement_matrix(p.position, b.centroid) * b.velocity;
}

std::string describe_contact(const BlockSystem& s, const Contact& c) {
  const Block& bi = s.blocks[c.block_i];
  std::ostringstream out;
  const Block& bj = s.blocks[c.block_j];
  const Vec2& p1 = s.vertices[c.vertex];
  const Vec2& p2 = s.vertices[c.edge];
  const Vec2& p3 = s.vertices[s.next_vertex(c.edge)];
  out << "contact of block '" << s.block_names[c.block_i] << "' vertex " << (c.vertex - bi.first_vertex) << " at ("
      << p1.x() << ", " << p1.y() << ") on edge " << (c.edge - bj.first_vertex) << " (" << p2.x() << ", " << p2.y()
      << ")-(" << p3.x() << ", " << p3.y() << ") of block '" << s.block_names[c.block_j] << "' ("
      << to_string(c.state) << ", gap " << c.normal_gap << " m)";
  return out.str();
}

// Running extremes of each measurement point.
void record_points(const BlockSystem& s, double time, double rest_speed, std::vector<PointSummary>& points) {
  for (size_t k = 0; k < s.points.size(); ++k) {
    const MaterialPoint& p = s.points[k];
    const Vec2 u = p.position - p.initial_position;
    const Vec2 v = point_velocity(s, p);
    PointSummary& sum = points[k];
    sum.max_lateral_displacement = std::max(sum.max_lateral_displacement, std::abs(u.x()));
    sum.max_total_displacement = std::max(sum.max_total_displacement, u.norm());
    sum.peak_lateral_velocity = std::max(sum.peak_lateral_velocity, std::abs(v.x()));
    sum.peak_total_velocity = std::max(sum.peak_total_velocity, v.norm());
    if (v.norm() >= rest_speed) sum.duration = time;
    sum.stopped = v.norm() < rest_speed;
  }
}

void record_history(const BlockSystem& s, double time, std::vector<HistoryRow>& history) {
  for (size_t k = 0; k < s.points.size(); ++k) {
    const MaterialPoint& p = s.points[k];
    history.push_back({time, static_cast<int>(k), p.position, p.position - p.initial_position,
                       point_velocity(s, p)});
  }
}

// The time step below which friction-induced vibration of the blocks' elastic modes
// is no longer damped by the time scheme: a fraction of the elastic period L / c of the
// largest free block (c = sqrt(E / rho); large blocks have the slowest modes, so they
// are the first to be resolved). Measured on the seed's incline (docs/verification.md,
// "Stability map"): 5e-4 s gave 0.06 % error, 2e-4 s gave 11 %, with L / c = 1.6 ms.
constexpr double kElasticPeriodFraction = 0.25;

// Settling may move a block by up to this many steps' worth of displacement: enough for
// the elastic shortening of a tall mass, not for a block that is falling over.
constexpr double kSettleShiftSteps = 10.0;

std::string time_step_warning(const Scene& scene, const BlockSystem& s) {
  double longest = 0.0;
  int which = -1;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.fixed) continue;
    const Material& m = scene.materials[block.material];
    const double period = std::sqrt(block.area) / std::sqrt(m.young_modulus / m.density);
    if (period > longest) {
      longest = period;
      which = b;
    }
  }
  if (which < 0 || scene.max_step >= kElasticPeriodFraction * longest) return {};
  std::ostringstream out;
  out << "time.step " << scene.max_step << " s is below " << kElasticPeriodFraction
      << " x the elastic period of block '" << s.block_names[which] << "' (" << longest
      << " s): friction can feed a spurious vibration of the blocks that lowers the mean friction "
         "(docs/theory.md, known limits); use time.step >= "
      << kElasticPeriodFraction * longest << " s";
  return out.str();
}

}  // namespace

SimulationResult simulate(const Scene& scene, const SimulationHooks& hooks) {
  const auto wall_start = std::chrono::steady_clock::now();
  SimulationResult result;
  SimulationSummary& summary = result.summary;
  const SimulationOptions& options = scene.options;
  if (const auto errors = validate_scene(scene); !errors.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = errors.front().key + ": " + errors.front().problem;
    return result;
  }

  BlockSystem system = build_block_system(scene);
  if (std::string w = time_step_warning(scene, system); !w.empty()) summary.warnings.push_back(w);
  for (const MeasurePoint& m : scene.measure) summary.points.push_back({m.name});
  TimeStepControl control =
      make_time_step_control(options, scene.max_step, system.half_model_size, automatic_penalty(scene));
  ContactSearch search;
  search.search_distance = options.search_distance_factor * control.max_displacement;
  search.first_step = true;

  // The springs and loads of one attempt at a step of length dt.
  const auto step_parameters = [&](double dt) {
    return StepParameters{dt, control.penalty, options.shear_penalty_ratio * control.penalty, scene.gravity,
                          options.contact_tolerance_ratio * control.max_displacement,
                          options.max_pushout_speed * dt};
  };
  std::vector<Contact> contacts, saved;
  BlockSparseMatrix k;
  Eigen::VectorXd f, d;
  SolverOptions solver_options;
  solver_options.reuse_factorization = options.reuse_factorization;
  SparseSolver solver(solver_options);
  StepProfile& profile = summary.profile;
  RunCounters& run = summary.run;
  run.smallest_step = scene.max_step;

  double time = 0.0;
  long output_count = 1;  // outputs at multiples of the interval, without summing round-off
  double next_output = scene.output_interval;
  const double end_slack = 1e-9 * scene.duration;

  if (options.settle_passes > 0) {
    // The contacts touching at t = 0 start loaded (forward/step/settle_contacts.hpp).
    std::string problem;
    {
      ScopedTimer timer(profile.find_contacts);
      problem = find_contacts(system, search, contacts);
    }
    if (!problem.empty()) {
      summary.status = RunStatus::InvalidScene;
      summary.message = "t = 0: " + problem;
      return result;
    }
    ScopedTimer timer(profile.settle);
    const StepParameters step = step_parameters(control.step);
    if (!settle_contacts(system, contacts, step, options.settle_passes, kSettleShiftSteps * control.max_displacement,
                         solver)) {
      summary.status = RunStatus::Failed;
      summary.message = "t = 0: the initial contact settling could not be solved: check for blocks that "
                        "overlap or a penalty far stiffer than the blocks";
      return result;
    }
  }

  record_points(system, time, scene.rest_speed, summary.points);
  record_history(system, time, result.history);
  if (hooks.on_output) hooks.on_output(time, system);
  auto last_progress = wall_start;

  const EnergyAudit audit = start_energy_audit(system, scene.gravity);

  auto fail = [&](RunStatus status, const std::string& why) {
    std::ostringstream out;
    out << "t = " << time << " s, step " << run.steps + 1 << ": " << why;
    summary.status = status;
    summary.message = out.str();
  };

  while (time < scene.duration - end_slack) {
    {
      ScopedTimer timer(profile.find_contacts);
      const std::string problem = find_contacts(system, search, contacts);
      if (!problem.empty()) {
        fail(RunStatus::InvalidScene, problem);
        break;
      }
    }
    search.first_step = false;
    saved = contacts;
    bool accepted = false;
    double attempt = 0.0;
    double landing = -1.0;  // the output time or end time this step lands on exactly, if any
    while (!accepted) {
      // A step within a hair of the next output (or the end) is stretched to land on
      // it, so that rows fall on multiples of the interval without round-off drift.
      attempt = control.step;
      landing = -1.0;
      const double target = scene.output_interval > 0.0 ? std::min(next_output, scene.duration) : scene.duration;
      if (target - time <= attempt * (1.0 + 1e-6)) {
        attempt = target - time;
        landing = target;
      }
      const StepParameters step = step_parameters(attempt);
      const OpenCloseResult oc =
          open_close_iterate(system, contacts, step, options, solver, k, f, d, profile);
      run.open_close_iterations += oc.iterations;
      run.unsettled_contacts += oc.unsettled;
      std::string why;
      double factor = options.step_cut_factor;
      if (!oc.converged) {
        why = oc.reason;
        if (oc.unsettled_contact >= 0) why += " at the " + describe_contact(system, contacts[oc.unsettled_contact]);
      } else if (const double moved = max_vertex_displacement(system, d); moved > control.max_displacement) {
        why = "a vertex moved " + std::to_string(moved) + " m in one step (limit " +
              std::to_string(control.max_displacement) + " m)";
        factor = std::clamp(0.8 * control.max_displacement / moved, 0.1, 0.9);
      } else {
        int deepest = -1;
        // Half the search distance: deeper, a contact is close to being lost altogether.
        const double depth =
            max_penetration(contacts, step, control.max_penetration, 0.5 * search.search_distance, &deepest);
        if (depth > control.max_penetration) {
          const std::string where = describe_contact(system, contacts[deepest]);
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
    ++run.steps;
    run.smallest_step = std::min(run.smallest_step, attempt);
    run.largest_step = std::max(run.largest_step, attempt);
    grow_step(control, options);
    record_points(system, time, scene.rest_speed, summary.points);
    if (const std::string problem = check_energy(audit, system, scene.gravity); !problem.empty()) {
      record_history(system, time, result.history);
      fail(RunStatus::Failed, problem);
      break;
    }

    const bool at_end = time >= scene.duration - end_slack;
    const bool at_output = scene.output_interval <= 0.0 || time >= next_output - end_slack;
    if (at_output || at_end) {
      record_history(system, time, result.history);
      if (hooks.on_output) hooks.on_output(time, system);
      while (scene.output_interval > 0.0 && next_output <= time + end_slack)
        next_output = static_cast<double>(++output_count) * scene.output_interval;
    }
    const auto now = std::chrono::steady_clock::now();
    if (hooks.on_progress && now - last_progress > std::chrono::seconds(1)) {
      hooks.on_progress(time, scene.duration);
      last_progress = now;
    }
  }
  run.simulated_time = time;
  run.symbolic_analyses = solver.counters().symbolic_analyses;
  run.factorizations = solver.counters().factorizations;
  run.cg_solves = solver.counters().cg_solves;
  run.final_penalty = control.penalty;
  profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace ddafit
