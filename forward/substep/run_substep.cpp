#include "forward/substep/run_substep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/common/containment_check.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/common/supported_blocks.hpp"
#include "forward/substep/block_stress.hpp"
#include "forward/substep/converge_impacts.hpp"
#include "forward/substep/integrate.hpp"
#include "forward/substep/prepare_contacts.hpp"
#include "forward/substep/solve_contacts.hpp"
#include "forward/substep/step_control.hpp"
#include "forward/substep/substep_context.hpp"

namespace ddafit {
namespace {

// Overlap tolerated without push-out, as a fraction of the largest displacement allowed
// per step: a contact pushed out to exactly zero chatters between touching and not.
constexpr double kSlopRatio = 1e-3;

// Share of the way to the contacts' mean stress a block's stress moves in one step
// (block_stress.hpp).
constexpr double kStressRelaxation = 0.1;

// A run stops when an overlap passes this fraction of the smaller block's size: the two
// blocks are then no longer separated by their contact (a block passing through another).
constexpr double kFailPenetrationRatio = 0.25;

// Relative normal velocity, as a fraction of the largest step displacement per step,
// that a touching point may keep after the last sweep and still count as converged.
constexpr double kConvergedVelocityRatio = 1e-2;

// The quiet start stops once no point's normal impulse changes over a step by more than
// kQuietStartTolerance of the largest, or after kQuietStartSteps steps. A slope that is
// not in equilibrium never gets there (its blocks slide a little between the restarts
// from rest): on Vajont section I the change fell to 0.4 % within 100 steps and on section
// VII to ~10 % within 50, and neither improved later. The full 500 steps are still needed:
// section IV released after 100 bounced, its kinetic energy reaching 4e7 J/m
// within 3 steps while its centroids rose (the audit stops that); after 300 it ran.
// A heavy block on a light one (mass ratio 100) needs the 1e-4: stopped at 1e-3 it rocked
// itself up within 0.06 s (test_substep_scenes.cpp); at 1e-4 it settles within 100
// steps and moves 2 um.
constexpr int kQuietStartSteps = 500;
constexpr double kQuietStartTolerance = 1e-4;

// Position correction after each step (solve_contacts.hpp): passes; the share of an
// overlap's excess removed per pass; the overlap it starts at, as a share of the smaller
// block (under half the 1 % the run is held to, so that a step's new overlap stays below it);
// and the largest correction per point and pass as a share of the largest move allowed per step.
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
constexpr double kDeepOverlap = 0.004;
constexpr double kCorrectionShare = 0.5;
// Split impulses' position update (integrate.hpp): a velocity change within a substep up to
// h x this many times gravity counts as the work of steady forces (trapezoidal move), the
// rest as an impact (the move follows the velocity after it). Twice gravity: free flight and
// a slide's friction stay exact (joint crossings within 2.1e-6 of seed Eq. 4-5), and an
// impact moves no deeper than h^2 g beyond what its contact allowed.
constexpr double kSmoothAccelerationRatio = 2.0;
// Extra relax sweeps per substep over the deep manifolds and their neighbours
// (solve_contacts.hpp, converge_deep).
constexpr int kDeepIterations = 16;
// Impact groups (converge_impacts.hpp), model revision 2026-11-27.10: a point still closing
// faster than kImpactClosingRatio x |g| h after the sweeps, or opening faster than
// kImpactSpentRatio x |g| h (at least kImpactSpentRestShare x rest_speed) while it pushes,
// starts a group. |g| h is what gravity adds to a speed in a substep. The margins and the
// rest_speed floor (a heavy block on a light one sank 4 mm without it) are measured in
// docs/theory.md §13, "Impact groups".
constexpr double kImpactClosingRatio = 10.0;
constexpr double kImpactSpentRatio = 3.0;
constexpr double kImpactSpentRestShare = 0.2;
// Steps after an impact in which its group's blocks are held to the tighter margin
// (ImpactConvergence::settle_substeps), model revision 2026-11-28.6.
constexpr int kImpactSettleSteps = 2;


// The deepest overlap at the end of the step, relative to the smaller block of its pair;
// and the points still closing after the last sweep.
void measure_contacts(SubstepContext& w, double time, double converged_speed) {
  const BlockSystem& s = w.system;
  SolverReport& report = w.report;
  for (const ContactManifold& m : w.contacts.manifolds) {
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      const double gap = current_gap(m, p, w.state.step_moves);
      const double vn = normal_rate(m, p, w.state.velocity);
      if (gap < 0.0 && vn < -converged_speed) ++report.unconverged_points;
      w.worst.note(s, m, -gap, time);
    }
    report.contact_points += m.point_count;
  }
  report_overlap(s, w.worst, report);
}

// Broad and narrow phase: this step's manifolds, carrying over the last step's impulses.
std::string detect(SubstepContext& w) {
  ScopedTimer timer(w.profile->find_contacts);
  w.detection.settings.extra_reach = w.extra_reach;
  return detect_contacts(w.system, w.detection, w.contacts);
}

// Masses, contact Jacobians and colours for substeps of length h, and the sweep settings.
SweepSettings prepare_step(SubstepContext& w, double h) {
  const BlockSystem& s = w.system;
  const SimulationOptions& o = w.options;
  const double slop = w.detection.settings.linear_slop;
  ScopedTimer timer(w.profile->assemble);
  compute_block_masses(s, w.state.masses);
  mask_sleeping(w.sleep, w.state.masses);
  water_accelerations(s, w.scene.gravity.norm(), h * w.options.substeps, w.state);
  prepare_contacts(w, h, kDeepOverlap);
  w.state.deep.assign(w.contacts.manifolds.size(), 0);
  w.state.of_block.reset();
  w.colours = colour_manifolds(s, w.contacts.manifolds);
  if (w.sleep.enabled()) drop_sleeping_manifolds(w.contacts.manifolds, w.state.masses, w.colours);
  // The contact spring at an eighth of the substep rate, Box2D's ratio (30 Hz at 240 Hz),
  // without its 30 Hz cap: at 30 Hz a stack of five 1 m blocks sank 1 cm into its
  // contacts; at a quarter of the rate a heavy block on a light one (mass ratio 100)
  // rocked itself up until the energy audit stopped it.
  const double hertz = o.contact_hertz > 0.0 ? o.contact_hertz : 0.125 / h;
  SweepSettings sweep;
  sweep.h = h;
  sweep.softness = make_softness(hertz, o.contact_damping_ratio, h);
  sweep.max_pushout_speed = o.max_pushout_speed;
  sweep.linear_slop = slop;
  sweep.manifold_passes = o.contact_passes;
  return sweep;
}

// One substep: integrate velocities (`gravity` less the ground's acceleration in an
// earthquake), warm start, soft sweep, move, relax sweep, slip. With split impulses
// (control.split_impulses): two sweeps without push-out, more sweeps where the move would
// go deep, the push-out sweep, move (an impact's move follows its velocity after).
void run_one_substep(SubstepContext& w, const SweepSettings& sweep, const Vec2& gravity) {
  SweepSettings relax = sweep;
  relax.use_bias = false;
  ScopedTimer timer(w.profile->solve);
  integrate_velocities(w.state, gravity, sweep.h, w.start_velocity);
  if (w.options.split_impulses) w.state.free_velocity = w.state.velocity;
  warm_start(w.contacts.manifolds, w.colours, w.state);
  if (w.options.split_impulses) {
    // Two sweeps: with one, a slider across joints 0.1 m apart on a 28 deg slope ran 1.8 %
    // short of seed Eq. 5 (tests/test_joint_crossing.cpp): friction at many manifolds of
    // one block converges over sweeps. Two cost what the soft step's two cost.
    solve_contacts(w.contacts.manifolds, w.colours, relax, w.state);
    solve_contacts(w.contacts.manifolds, w.colours, relax, w.state);
    // Without gravity, the speed the run counts as converged (measure_contacts) stands for |g| h.
    const double g = gravity.norm();
    const double scale = g > 0.0 ? g * sweep.h : kConvergedVelocityRatio * w.max_move / (sweep.h * w.options.substeps);
    ImpactConvergence impacts;
    impacts.closing = kImpactClosingRatio * scale;
    impacts.spent = std::max(kImpactSpentRatio * scale, kImpactSpentRestShare * w.scene.rest_speed);
    impacts.settle_substeps = kImpactSettleSteps * w.options.substeps;
    if (g > 0.0) impacts.down = gravity / g;
    const ImpactCounts counts =
        w.settling ? ImpactCounts{} : converge_impacts(w.contacts.manifolds, relax, impacts, w.state);
    w.report.impact_groups += counts.solved;
    w.report.impact_groups_too_large += counts.too_large;
    w.report.impact_group_pieces += counts.pieces;
    w.report.impact_groups_refused += counts.refused;
    flag_closing_deep(w.contacts.manifolds, sweep.h, w.state);
    converge_deep(w.contacts.manifolds, relax, kDeepIterations, w.state, sweep.h);
    push_out_overlaps(w.contacts.manifolds, w.colours, sweep, w.state);
    integrate_positions(w.state, sweep.h, w.start_velocity, w.moves, kSmoothAccelerationRatio * gravity.norm());
    add_push_out_moves(w.state, sweep.h, w.moves);
  } else {
    solve_contacts(w.contacts.manifolds, w.colours, sweep, w.state);
    integrate_positions(w.state, sweep.h, w.start_velocity, w.moves);
    solve_contacts(w.contacts.manifolds, w.colours, relax, w.state);
    converge_deep(w.contacts.manifolds, relax, kDeepIterations, w.state);
  }
  advance_slip(w.system, w.moves, sweep.h, w.contacts);
}

// A step of length dt on this step's manifolds: substeps, then the blocks move (once,
// exactly: move_blocks) and each deformable block takes its stress from its contacts
// (block_stress.hpp). A measured step from w.time feels the earthquake, each substep the
// ground's mean acceleration over it; the quiet start's steps, before the clock runs, do not.
void advance(SubstepContext& w, double dt, bool measured) {
  BlockSystem& s = w.system;
  const int substeps = w.options.substeps;
  const SweepSettings sweep = prepare_step(w, dt / substeps);
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    w.state.velocity[b] = s.blocks[b].velocity.head<3>();
    w.state.step_moves[b].setZero();
  }
  const bool shaking = measured && w.ground.present();
  w.load_work = 0.0;
  for (int k = 0; k < substeps; ++k) {
    const double t0 = w.time + k * sweep.h;
    const Vec2 ground = shaking ? w.ground.mean_acceleration(t0, t0 + sweep.h) : Vec2::Zero();
    run_one_substep(w, sweep, w.scene.gravity - ground);
    if (!shaking) continue;
    // The load -m a_g of this substep over this substep's moves (the energy audit).
    Vec2 moved = Vec2::Zero();
    for (size_t b = 0; b < s.blocks.size(); ++b)
      if (w.state.masses[b].moves) moved += s.mass(static_cast<int>(b)) * w.moves[b].head<2>();
    w.load_work -= ground.dot(moved);
  }
  {
    ScopedTimer timer(w.profile->solve);
    correct_positions(w.contacts.manifolds, w.correction, w.state);
  }
  ScopedTimer timer(w.profile->update);
  move_blocks(s, w.state, measured);
  update_block_stress(w, dt, kStressRelaxation, measured);
}

// The normal impulses of the last substep, point by point in manifold order.
void last_normal_impulses(const std::vector<ContactManifold>& manifolds, std::vector<double>& out) {
  out.clear();
  for (const ContactManifold& m : manifolds)
    for (int q = 0; q < m.point_count; ++q) out.push_back(m.points[q].impulse.normal);
}

// Largest change of any point's normal impulse over the step, relative to the largest:
// `before` holds the impulses each point carried into the step (zero for a new point).
double impulse_change(const std::vector<ContactManifold>& manifolds, const std::vector<double>& before) {
  double largest = 0.0, change = 0.0;
  size_t i = 0;
  for (const ContactManifold& m : manifolds)
    for (int q = 0; q < m.point_count; ++q, ++i) {
      largest = std::max(largest, std::abs(m.points[q].impulse.normal));
      change = std::max(change, std::abs(m.points[q].impulse.normal - before[i]));
    }
  return largest > 0.0 ? change / largest : 0.0;
}

// Quiet start: the contacts touching at t = 0 take up the weight before the clock runs, for
// the blocks resting on the ground (common/supported_blocks.hpp).
// Steps of the scene's length with those blocks at rest before each (a given velocity
// waits for the clock: until revision 2026-11-27.7 the first step carried a touching block
// v dt before t = 0, 5 cm for a block given 5 m/s at 10 ms, tests/test_impact_depth.cpp), their
// strain following their contacts, until no normal impulse changes by more than
// kQuietStartTolerance of the largest. Blocks in flight stay exactly as given, held still:
// through revision 2026-11-27.8 they kept their velocity while held, so a block given 2 m/s
// 1 mm above a stack pressed it down 5.6 mm through the quiet start and the impulses built up
// launched everything at the first step (tests/test_impact_rebound.cpp); the
// measurement points' origins move with the blocks, and no slip is counted: the slide
// starts from rest, not with a bounce.
std::string quiet_start(SubstepContext& w) {
  BlockSystem& s = w.system;
  CollideSettings& settings = w.detection.settings;
  ScopedTimer timer(w.profile->settle);
  StepProfile* const run_profile = w.profile;
  StepProfile ignored;
  w.profile = &ignored;
  const auto restore = [&] { w.profile = run_profile; };
  if (std::string problem = detect(w); !problem.empty()) {
    restore();
    return problem;
  }
  const std::vector<char> resting = supported_blocks(s, w.contacts.manifolds, settings.linear_slop);
  std::vector<Vec6> initial(s.blocks.size());
  std::vector<char> was_fixed(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    initial[b] = s.blocks[b].velocity;
    was_fixed[b] = s.blocks[b].fixed;
    if (!resting[b]) s.blocks[b].fixed = true;  // in flight: takes no part
  }
  std::vector<double> before;
  w.settling = true;
  for (int k = 0; k < kQuietStartSteps; ++k) {
    if (k > 0) detect(w);
    last_normal_impulses(w.contacts.manifolds, before);
    for (size_t b = 0; b < s.blocks.size(); ++b)  // held blocks too: a held block's velocity
      if (!was_fixed[b]) s.blocks[b].velocity.setZero();  // still drives its contacts
    advance(w, w.scene.max_step, false);
    if (impulse_change(w.contacts.manifolds, before) <= kQuietStartTolerance) break;
  }
  w.settling = false;
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    s.blocks[b].fixed = was_fixed[b];
    s.blocks[b].velocity = initial[b];
  }
  reset_histories(s, w.contacts);
  settings.first_step = true;  // bonds form between the blocks touching once settled
  restore();
  return {};
}

// Every free block asleep (everything_asleep): the blocks stay as they are, so the rest of
// the run is this state at each output time, recorded without steps.
void rest_to_the_end(RunRecorder& recorder, double& time, const BlockSystem& s) {
  while (!recorder.finished(time) && !recorder.interrupted(time, s)) {
    double landing = -1.0;
    const double dt = recorder.fit_step(time, std::numeric_limits<double>::infinity(), &landing);
    time = landing >= 0.0 ? landing : time + dt;
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
  w.reach.assign(n, 0.0);
  w.near.assign(n, 1);
  w.extra_reach.assign(n, 0.0);
  for (const Material& m : scene.materials) w.deformable.push_back(!(m.rigid || o.rigid_blocks));
  const double max_move = o.max_displacement_ratio * s.half_model_size;
  w.max_move = max_move;
  w.ground = GroundTrack(scene.earthquake);
  // Sleeping (sleep.hpp): not under an earthquake, whose load changes every step.
  w.sleep.sleep_time = w.ground.present() ? 0.0 : o.sleep_time;
  w.sleep.sleep_speed = o.sleep_speed > 0.0 ? o.sleep_speed : 0.01 * scene.rest_speed;
  w.sleep.rest_time.assign(n, 0.0);
  w.sleep.asleep.assign(n, 0);
  CollideSettings& settings = w.detection.settings;
  settings.margin = o.search_distance_factor * max_move;
  settings.linear_slop = kSlopRatio * max_move;
  settings.first_step = true;
  settings.gravity = scene.gravity;
  w.correction = {kCorrectionPasses, kCorrectionExtraPasses, kCorrectionFraction, kCorrectionShare * max_move};
  report.substeps = o.substeps;
  double time = 0.0;
  if (std::string problem = quiet_start(w); !problem.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "t = 0: " + problem;
    return;
  }
  EnergyAudit audit = start_energy_audit(s, scene.gravity);
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

  while (!recorder.finished(time) && !recorder.interrupted(time, s)) {
    mark_near(w);
    step = choose_step(w, step);
    double landing = -1.0;
    const double dt = recorder.fit_step(time, step, &landing);
    speculative_reach(w, dt);
    if (std::string problem = detect(w); !problem.empty()) {
      summary.status = RunStatus::InvalidScene;
      std::ostringstream out;
      out << "t = " << time << " s, step " << run.steps + 1 << ": " << problem;
      summary.message = out.str();
      return;
    }
    wake_touched_groups(s, w.contacts, w.reach, w.sleep);
    w.time = time;
    advance(w, dt, true);
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
    if (const std::string problem = check_containment(s); !problem.empty()) {
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
