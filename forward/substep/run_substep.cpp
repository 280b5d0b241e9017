#include "forward/substep/run_substep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/common/containment_check.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/common/supported_blocks.hpp"
#include "forward/substep/advance_step.hpp"
#include "forward/substep/sleep.hpp"
#include "forward/substep/solve_contacts.hpp"
#include "forward/substep/step_control.hpp"
#include "forward/substep/substep_context.hpp"

namespace ddafit {
namespace {

// A run stops when an overlap passes this fraction of the smaller block's size: the two
// blocks are then no longer separated by their contact (a block passing through another).
constexpr double kFailPenetrationRatio = 0.25;

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
  if (std::string problem = find_step_contacts(w); !problem.empty()) {
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
    w.threads.begin_step();
    if (k > 0) find_step_contacts(w);
    last_normal_impulses(w.contacts.manifolds, before);
    for (size_t b = 0; b < s.blocks.size(); ++b)  // held blocks too: a held block's velocity
      if (!was_fixed[b]) s.blocks[b].velocity.setZero();  // still drives its contacts
    advance_step(w, w.scene.max_step, false);
    w.threads.end_step();
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

// Blocks that the quiet start turned by more than this, rad, are named in a warning: the run
// starts them away from where they were given (docs/theory.md, Known limits (k)). Vajont's
// sections at their own steps turn no block by more than 7.1e-3 rad there (section X); a block
// resting on its corner at too long a step turns by its whole tilt (tests/test_rocking.cpp).
constexpr double kQuietStartTurnWarning = 0.01;
// The step, as a share of sqrt(L / |g|) (L a block's size, the square root of its area), up to
// which a block resting on its corner keeps its tilt through the quiet start: at 0.03 every block
// of the class of tests/test_rocking.cpp (0.1-10 m, H/b 3 and 6, tilted 0.1-0.6 of its critical
// angle, one and four substeps) starts within 0.7 % of its tilt; at 0.05 those tilted 0.1 fall.
constexpr double kKeepsTiltStepRatio = 0.03;

// The warning for the block the quiet start turned most, if it turned more than
// kQuietStartTurnWarning; `given` holds the vertices before the quiet start.
std::string quiet_start_warning(const Scene& scene, const BlockSystem& s, const std::vector<Vec2>& given) {
  double most = 0.0;
  int which = -1;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.fixed) continue;
    const Vec2 before = given[block.first_vertex + 1] - given[block.first_vertex];
    const Vec2 after = s.vertices[block.first_vertex + 1] - s.vertices[block.first_vertex];
    const double turn = std::abs(std::atan2(before.x() * after.y() - before.y() * after.x(), before.dot(after)));
    if (turn > most) most = turn, which = b;
  }
  if (which < 0 || most <= kQuietStartTurnWarning) return {};
  const double size = std::sqrt(s.blocks[which].area), g = scene.gravity.norm();
  std::ostringstream out;
  out.precision(3);
  out << "block '" << s.block_names[which] << "' turned " << most * 180.0 / M_PI
      << " deg before t = 0, while the contacts took up the weight from rest (the quiet start): it is not in "
         "equilibrium where it was given, and the run starts it turned (docs/theory.md, known limits (k)); ";
  const double keeps = g > 0.0 ? kKeepsTiltStepRatio * std::sqrt(size / g) : 0.0;
  if (scene.max_step > keeps && keeps > 0.0)
    out << "time.step " << scene.max_step << " s is long for it (a block of its size, " << size
        << " m, resting on a corner keeps its tilt at steps up to about " << keeps << " s), or use ";
  else
    out << "use ";
  out << "time.integrator: implicit, whose settling holds a falling block where it was given";
  return out.str();
}

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
  w.reach.assign(n, 0.0);
  w.near.assign(n, 1);
  w.extra_reach.assign(n, 0.0);
  for (const Material& m : scene.materials) w.deformable.push_back(!(m.rigid || o.rigid_blocks));
  const double max_move = o.max_displacement_ratio * s.half_model_size;
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
  const std::vector<Vec2> given_vertices = s.vertices;
  if (std::string problem = quiet_start(w); !problem.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "t = 0: " + problem;
    return;
  }
  if (std::string turned = quiet_start_warning(scene, s, given_vertices); !turned.empty())
    summary.warnings.push_back(std::move(turned));
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
