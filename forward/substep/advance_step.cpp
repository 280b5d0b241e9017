#include "forward/substep/advance_step.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "forward/contact/detect_contacts.hpp"
#include "forward/contact/overlap.hpp"
#include "forward/parallel.hpp"
#include "forward/run_record.hpp"
#include "forward/substep/block_stress.hpp"
#include "forward/substep/converge_heavy.hpp"
#include "forward/substep/converge_impacts.hpp"
#include "forward/substep/integrate.hpp"
#include "forward/substep/prepare_contacts.hpp"
#include "forward/substep/refresh_corner_gaps.hpp"
#include "forward/substep/sleep.hpp"
#include "forward/substep/solve_contacts.hpp"

namespace ddafit {
namespace {


// Share of the way to the contacts' mean stress a block's stress moves in one step
// (block_stress.hpp).
constexpr double kStressRelaxation = 0.1;

// Split impulses' position update (integrate.hpp): a velocity change within a substep up to
// h x this many times gravity counts as the work of steady forces (trapezoidal move), the
// rest as an impact (the move follows the velocity after it). Twice gravity: free flight and
// a slide's friction stay exact (joint crossings within 2.1e-6 of seed Eq. 4-5), and an
// impact moves no deeper than h^2 g beyond what its contact allowed.
constexpr double kSmoothAccelerationRatio = 2.0;
// Extra relax sweeps per substep over the deep manifolds and their neighbours
// (solve_contacts.hpp, converge_deep).
constexpr int kDeepIterations = 16;
// Extra relax sweeps per substep over the manifolds of a block beside one at least
// kHeavyMassRatio times heavier (converge_heavy.hpp), model revision 2026-12-05.2. On the
// cube-row class at 2 ms x 4 (tests/test_free_row.cpp) 8 sweeps at a ratio of 30 mend all 18
// runs of a slider 450 times a cube (12 off with none); at 5 ms x 4, 12 of 72 stay off (28
// with none; 16 sweeps: 7, 32: 2). The cost is in Vajont's meshes, whose slivers lie beside
// blocks up to hundreds of times heavier: on section VII degraded's first 10 s the list holds
// 2 % of the manifolds at a ratio of 30 (12 % at 10), and 16 sweeps took 8 % more wall than
// none, 32 sweeps 23 %.
constexpr double kHeavyMassRatio = 30.0;
constexpr int kHeavySweeps = 8;
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

}  // namespace

void measure_contacts(SubstepContext& w, double time, double converged_speed) {
  const BlockSystem& s = w.system;
  SolverReport& report = w.report;
  const std::vector<ContactManifold>& manifolds = w.contacts.manifolds;
  const long n = static_cast<long>(manifolds.size());
  // Each thread measures one contiguous share, in order, from the worst so far; the shares'
  // worst are then taken in order, each only if strictly worse, so the first of equal
  // overlaps is kept on any number of threads, as on one.
  const int most = n >= kParallelMinimum ? omp_get_max_threads() : 1;
  std::vector<WorstOverlap> worst(most, w.worst);
  std::vector<long> unconverged(most, 0), points(most, 0);
  int used = 1;
#pragma omp parallel num_threads(most) if (most > 1)
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
#pragma omp single
    used = threads;
    const ThreadShare share = thread_share(n, t, threads);
    for (long k = share.first; k < share.last; ++k) {
      const ContactManifold& m = manifolds[k];
      for (int q = 0; q < m.point_count; ++q) {
        const ContactPoint& p = m.points[q];
        const double gap = current_gap(m, p, w.state.step_moves);
        const double vn = normal_rate(m, p, w.state.velocity);
        if (gap < 0.0 && vn < -converged_speed) ++unconverged[t];
        worst[t].note(s, m, -gap, time);
      }
      points[t] += m.point_count;
    }
  }
  for (int t = 0; t < used; ++t) {
    if (worst[t].ratio > w.worst.ratio) w.worst = worst[t];
    report.unconverged_points += unconverged[t];
    report.contact_points += points[t];
  }
  report_overlap(s, w.worst, report);
}

std::string find_step_contacts(SubstepContext& w) {
  ScopedTimer timer(w.profile->find_contacts);
  w.detection.settings.extra_reach = w.extra_reach;
  return detect_contacts(w.system, w.detection, w.contacts);
}

namespace {

// Masses, contact Jacobians and colours for substeps of length h, and the sweep settings.
SweepSettings prepare_step(SubstepContext& w, double h) {
  const BlockSystem& s = w.system;
  const SimulationOptions& o = w.options;
  const double slop = w.detection.settings.linear_slop;
  ScopedTimer timer(w.profile->assemble);
  compute_block_masses(s, w.state.masses);
  mask_sleeping(w.sleep, w.state.masses);
  water_accelerations(s, w.scene.gravity.norm(), h * w.options.substeps, w.state);
  prepare_contacts(w, h, w.deep_overlap_ratio, w.last_substep > 0.0 ? h / w.last_substep : 1.0);
  w.last_substep = h;
  w.state.deep.assign(w.contacts.manifolds.size(), 0);
  remember_corner_points(w.contacts.manifolds, w.state);
  w.state.of_block.reset();
  w.state.heavy.reset();
  const double g = w.scene.gravity.norm();
  w.colours = colour_manifolds(s, w.contacts.manifolds, g > 0.0 ? Vec2(-w.scene.gravity / g) : Vec2::Zero());
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
  refresh_corner_gaps(w.system, w.detection.shapes, sweep.h, sweep.linear_slop, w.contacts.manifolds, w.state);
  warm_start(w.contacts.manifolds, w.colours, w.state);
  if (w.options.split_impulses) {
    // Two sweeps: with one, a slider across joints 0.1 m apart on a 28 deg slope ran 1.8 %
    // short of seed Eq. 5 (tests/test_joint_crossing.cpp): friction at many manifolds of
    // one block converges over sweeps. Two cost what the soft step's two cost.
    solve_contacts(w.contacts.manifolds, w.colours, relax, w.state);
    solve_contacts(w.contacts.manifolds, w.colours, relax, w.state);
    converge_heavy(w.contacts.manifolds, relax, {kHeavyMassRatio, kHeavySweeps}, w.state);
    // Without gravity, the speed the run counts as converged (measure_contacts) stands for |g| h.
    const double g = gravity.norm();
    const double scale = g > 0.0 ? g * sweep.h : kConvergedVelocityRatio * w.max_move / (sweep.h * w.options.substeps);
    ImpactConvergence impacts;
    impacts.closing = kImpactClosingRatio * scale;
    impacts.spent = std::max(kImpactSpentRatio * scale, kImpactSpentRestShare * w.scene.rest_speed);
    impacts.settle_substeps = kImpactSettleSteps * w.options.substeps;
    if (g > 0.0) impacts.down = gravity / g;
    impacts.heavy_mass_ratio = kHeavyMassRatio;
    const ImpactCounts counts =
        w.settling ? ImpactCounts{} : converge_impacts(w.contacts.manifolds, relax, impacts, w.state);
    w.report.impact_groups += counts.solved;
    w.report.impact_groups_too_large += counts.too_large;
    w.report.impact_group_pieces += counts.pieces;
    w.report.impact_groups_refused += counts.refused;
    w.report.impact_groups_with_friction += counts.with_friction;
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
  advance_slip(w.system, w.moves, sweep.h, sweep.linear_slop, w.contacts);
}

}  // namespace

// A step of length dt on this step's manifolds: substeps, then the blocks move (once,
// exactly: move_blocks) and each deformable block takes its stress from its contacts
// (block_stress.hpp). A measured step from w.time feels the earthquake, each substep the
// ground's mean acceleration over it; the quiet start's steps, before the clock runs, do not.
void advance_step(SubstepContext& w, double dt, bool measured) {
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

}  // namespace ddafit
