#include "forward/substep/run_substep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/common/containment_check.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/substep/advance_step.hpp"
#include "forward/substep/quiet_start.hpp"
#include "forward/substep/sleep.hpp"
#include "forward/substep/solve_contacts.hpp"
#include "forward/substep/step_control.hpp"
#include "forward/substep/substep_context.hpp"

namespace ddafit {
namespace {

// A run stops when an overlap passes this fraction of the smaller block's size: the two
// blocks are then no longer separated by their contact (a block passing through another).
constexpr double kFailPenetrationRatio = 0.25;

// Position correction after each step (solve_contacts.hpp): passes; the share of an
// overlap's excess removed per pass (from the overlap it starts at, control.deep_overlap_ratio
// of the smaller block, options.hpp); and the largest correction per point and pass as a share
// of the largest move allowed per step.
// Eight passes of up to half a move: with three of a fifth, a light block jammed between
// heavy ones kept 1.9 % of its size (Vajont IV degraded) and 1.0 % (V); with eight of a half,
// 0.47 % and 0.59 %. The passes run only where a relax sweep found a point deep.
constexpr int kCorrectionPasses = 8;
// Up to 8 more passes while the last one still corrected (model revision 2026-11-27.6): on
// Vajont section X degraded the 8th pass closed an open pair 5.6 cm (1.13 % of its smaller
// block) while pushing its blocks out of deep neighbours, and nothing followed it; with the
// extra passes 0.54 % (section VII degraded 0.76 -> 0.59 %, at the same cost).
constexpr int kCorrectionExtraPasses = 8;
constexpr double kCorrectionFraction = 0.8;
constexpr double kCorrectionShare = 0.5;

// What the overlaps the quiet start leaves can give back as they open, J/m
// (EnergyAudit::stored_contact): each point's load of the last substep times its depth now.
double stored_contact_energy(const std::vector<ContactManifold>& manifolds, const std::vector<Vec3>& step_moves) {
  double energy = 0.0;
  for (const ContactManifold& m : manifolds)
    for (int q = 0; q < m.point_count; ++q)
      energy += m.points[q].normal_load * std::max(0.0, -current_gap(m, m.points[q], step_moves));
  return energy;
}

// Every free block asleep (everything_asleep): the blocks stay as they are, so the rest of
// the run is this state at each output time, recorded without steps.
void rest_to_the_end(RunRecorder& recorder, double& time, const BlockSystem& s) {
  while (!recorder.finished(time) && !recorder.interrupted(time, s)) {
    double landing = -1.0;  // an unbounded step always lands on the next output time (or the end)
    recorder.fit_step(time, std::numeric_limits<double>::infinity(), &landing);
    time = landing;
    recorder.record(time, s);
  }
}

}  // namespace

void run_substep(const Scene& scene, BlockSystem& s, RunRecorder& recorder, SimulationSummary& summary) {
  const SimulationOptions& o = scene.options;
  SolverReport& report = summary.solver;
  StepProfile& profile = summary.profile;
  RunCounters& run = summary.run;
  SubstepContext w(scene, s, summary);
  if (const std::string bad = prepare_detection(s, w.detection); !bad.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "block '" + bad + "': its polygon could not be split into convex pieces for contact";
    return;
  }
  prepare_shear_bands(s, scene.duration, w.contacts);
  const size_t n = s.blocks.size();
  w.start_velocity.assign(n, Vec3::Zero());
  w.moves.assign(n, Vec3::Zero());
  w.state.velocity.assign(n, Vec3::Zero());
  w.state.step_moves.assign(n, Vec3::Zero());
  w.state.bonds = std::any_of(scene.interfaces.begin(), scene.interfaces.end(),
                              [](const Interface& f) { return f.cohesion > 0.0 || f.tensile_strength > 0.0; });
  w.reach.assign(n, 0.0);
  w.near.assign(n, 1);
  w.extra_reach.assign(n, 0.0);
  for (const Material& m : scene.materials) w.deformable.push_back(!(m.rigid || o.rigid_blocks));
  const double max_move = step_move_limit(o.max_displacement_ratio, s);
  w.max_move = max_move;
  w.deep_overlap_ratio = deep_overlap_ratio(o.deep_overlap_ratio, s.free_block_count);
  report.deep_overlap_ratio = w.deep_overlap_ratio;
  w.ground = GroundTrack(scene.earthquake);
  // Sleeping (sleep.hpp): not under an earthquake, whose load changes every step.
  w.sleep.sleep_time = w.ground.present() ? 0.0 : o.sleep_time;
  w.sleep.sleep_speed = o.sleep_speed > 0.0 ? o.sleep_speed : 0.01 * scene.rest_speed;
  w.sleep.rest_time.assign(n, 0.0);
  w.sleep.asleep.assign(n, 0);
  CollideSettings& settings = w.detection.settings;
  set_run_tolerances(settings, o.search_distance_factor, max_move);
  settings.first_step = true;
  settings.gravity = scene.gravity;
  const double longest_substep = scene.max_step / o.substeps;
  settings.sag = kSagRatio * scene.gravity.norm() * longest_substep * longest_substep;
  w.correction = {kCorrectionPasses, kCorrectionExtraPasses, kCorrectionFraction, kCorrectionShare * max_move};
  report.substeps = o.substeps;
  double time = 0.0;
  StepStart step_start;  // the centroids before a step, for the containment check
  remember_step_start(s, step_start);
  if (std::string problem = settle_before_the_clock(w, summary.warnings); !problem.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "t = 0: " + problem;
    return;
  }
  const long settling_on_one = w.threads.steps_on_one();  // the quiet start's are not the run's
  EnergyAudit audit = start_energy_audit(s, scene.gravity);
  audit.stored_contact = stored_contact_energy(w.contacts.manifolds, w.state.step_moves);
  report.stored_contact_energy = audit.stored_contact;
  recorder.start(s);
  double step = scene.max_step;
  run.smallest_step = scene.max_step;

  auto fail = [&](const std::string& why) {
    std::ostringstream out;
    out << "t = " << time << " s, step " << run.steps + 1 << ": " << why;
    summary.status = RunStatus::Failed;
    summary.message = out.str();
    run.simulated_time = time;
    recorder.record_row(time, s);
  };

  // The quiet start's steps are as long as the run's and the blocks in them as free: a step
  // too long for the contacts to take up the weight lets a block fall through its ground
  // before the clock runs (the stack of five 1 m blocks at 0.3 s steps; tests/test_stability.cpp).
  if (const std::string problem = check_containment(s, &step_start); !problem.empty()) {
    fail("while the contacts took up the weight before the clock ran (the quiet start), " + problem);
    return;
  }
  while (!recorder.finished(time) && !recorder.interrupted(time, s)) {
    remember_step_start(s, step_start);
    w.threads.begin_step();
    mark_near(w);
    step = choose_step(w, step);
    double landing = -1.0;
    const double dt = recorder.even_step(time, step, &landing);
    speculative_reach(w, dt);
    settings.slip_step = dt / o.substeps;
    if (std::string problem = find_step_contacts(w); !problem.empty()) {
      summary.status = RunStatus::InvalidScene;
      std::ostringstream out;
      out << "t = " << time << " s, step " << run.steps + 1 << ": " << problem;
      summary.message = out.str();
      return;
    }
    wake_touched_groups(s, w.contacts, w.reach, w.sleep);
    w.time = time;
    advance_step(w, dt, true);
    update_sleep(s, w.contacts, w.reach, dt, w.sleep);
    report.sleeping_block_steps = w.sleep.block_steps_asleep;
    report.wakes = w.sleep.wakes;
    audit.load_work += w.load_work;
    time = landing >= 0.0 ? landing : time + dt;
    ++run.steps;
    run.smallest_step = std::min(run.smallest_step, dt);
    run.largest_step = std::max(run.largest_step, dt);
    {
      ScopedTimer timer(profile.check_contacts);
      measure_contacts(w, time, kConvergedVelocityRatio * max_move / dt);
      if (largest_move(w) > 0.5 * settings.margin) ++report.fast_steps;
    }
    recorder.record(time, s);
    w.threads.end_step();
    report.steps_on_one_thread = w.threads.steps_on_one() - settling_on_one;
    if (report.worst_penetration_ratio > kFailPenetrationRatio) {
      std::ostringstream why;
      why << "an overlap of " << report.worst_penetration << " m between " << report.worst_penetration_at << " is "
          << report.worst_penetration_ratio << " of the smaller block's size: the contacts no longer hold the blocks "
          << "apart. Raise time.substeps (now " << o.substeps << ") or lower time.step";
      fail(why.str());
      return;
    }
    if (const std::string problem = check_energy(audit, s, scene.gravity); !problem.empty()) {
      fail(problem);
      return;
    }
    if (const std::string problem = check_containment(s, &step_start); !problem.empty()) {
      fail(problem);
      return;
    }
    if (everything_asleep(s, w.sleep)) {
      report.all_asleep_time = time;
      rest_to_the_end(recorder, time, s);
    }
  }
  run.simulated_time = time;
}

}  // namespace ddafit
