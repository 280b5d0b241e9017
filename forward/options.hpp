// Control settings of a DDA run. Plain data with documented defaults, validated once
// by validate_options() before a run (Ceres' Solver::Options is the model).
#pragma once

#include <string>

namespace ddafit {

// Which solver advances the blocks (docs/theory.md, "Two solvers").
enum class Integrator {
  Implicit,  // Shi's global solve with the open-close iteration: exact on the analytic checks
  Substep,   // velocity-level impulses in substeps: cost proportional to the contacts
  Auto,      // Substep from kAutoSubstepBlocks free blocks up or for a known limit's class, Implicit else
  Sled,      // fidelity 0: the free blocks as one flexible sled along the ground (forward/sled/)
};

// The rule of Integrator::Auto: from this many free blocks the implicit solver's global
// factorisation (cost ~ N^2.7 on Vajont sections I-II) loses to the substep solver's
// per-contact sweeps (docs/speed-accuracy.md).
inline constexpr int kAutoSubstepBlocks = 100;

const char* to_string(Integrator integrator);

// control.deep_overlap_ratio's automatic values (model revision 2026-12-05.9). Below
// kAutoSubstepBlocks free blocks: 2.5e-4. Squat sliders (r = tan phi H / L = 0.5) from rest on
// free rows of blocks 1.8-290 times lighter, 1 deg steeper than their friction, at 10 ms x 4:
// 14 of 18 runs more than 1 % off seed Eq. 4 at 4e-3, 12 at 1e-3, 2 at 5e-4, none at 2.5e-4
// (tests/test_heavy_sliders.cpp); the whole test suite passes at 2.5e-4 in the same wall.
// From kAutoSubstepBlocks up: 4e-3 (under half the 1 % a run is held to, so that a step's new
// overlap stays below 1 %). Landslide meshes pay for a lower value: Vajont section VII degraded
// took 269 s at 5e-4 against 129 s (its solve stage 2.8 times as long), and its
// worst overlap stayed 0.69 % (docs/performance.md).
inline constexpr double kDeepOverlapSmallScene = 2.5e-4;
inline constexpr double kDeepOverlapLargeScene = 4e-3;
// The value a run of `free_blocks` free blocks uses.
inline double deep_overlap_ratio(double asked, int free_blocks) {
  if (asked > 0.0) return asked;
  return free_blocks < kAutoSubstepBlocks ? kDeepOverlapSmallScene : kDeepOverlapLargeScene;
}

struct SimulationOptions {
  // time.integrator: implicit | substep | auto.
  Integrator integrator = Integrator::Auto;
  // Largest vertex displacement allowed in one step, as a fraction of half the model
  // size (Shi's "g2"; field notes: 0.001-0.01). A step that moves further is redone
  // with a shorter time step.
  double max_displacement_ratio = 0.005;

  // Normal contact penalty in N/m (per metre of thickness). 0 means automatic:
  // penalty_factor x the largest Young's modulus in the scene (Shi's rule of thumb).
  double penalty = 0.0;
  double penalty_factor = 50.0;

  // Shear spring of a locked contact = shear_penalty_ratio x normal penalty (Shi: 1/2.5).
  double shear_penalty_ratio = 0.4;

  // Open-close passes allowed before the step is redone with a shorter time step.
  int max_open_close_iterations = 8;

  // Time step control: cut factor on failure, growth factor per calm step (<= 1.3 per
  // field notes), and the shortest step, as a fraction of time.step, before the run is
  // declared failed.
  double step_cut_factor = 0.3;
  double step_growth_factor = 1.3;
  double min_step_ratio = 1.0e-6;

  // Largest penetration of a closed contact, as a fraction of half the model size
  // (Shi: 2.5 x 0.0004). Deeper contacts raise the penalty and redo the step, at most
  // max_penalty_raises times in one step; the penalty relaxes back when calm.
  double max_penetration_ratio = 1.0e-3;
  double penalty_raise_factor = 3.0;
  int max_penalty_raises = 6;

  // Contact tolerance as a fraction of the largest displacement allowed per step: gaps
  // and back-slips smaller than this do not change a contact's state (assemble.hpp).
  double contact_tolerance_ratio = 1e-7;

  // Speed, m/s, at which a contact found already deeper than the step can mend (a
  // corner that came round a corner) is pushed back out: its spring is unloaded at
  // its start-of-step gap plus max_pushout_speed x dt, plus the overlap its load held
  // (forward/step/assemble.hpp).
  double max_pushout_speed = 1.0;

  // Contact search distance as a multiple of the largest displacement allowed per step.
  double search_distance_factor = 2.5;

  // Largest number of static passes that pre-load the contacts touching at t = 0
  // (forward/step/settle_contacts.hpp; they stop when converged); 0 starts the
  // dynamics with unloaded springs.
  int settle_passes = 40;

  // Plane strain (default, long slopes) or plane stress elasticity.
  bool plane_strain = true;

  // Solve by conjugate gradients preconditioned with the last Cholesky factor while
  // that is cheaper than refactorising (forward/sparse_system.hpp). Off by default: on
  // Vajont section IV the open-close passes change hundreds of contacts at once, CG
  // converged in only 26 % of its attempts and the run took 1.36x as long
  // (docs/performance.md). false refactorises on every pass, as published DDA codes do.
  bool reuse_factorization = false;

  // Between open-close passes of a step only the contact points that changed state differ
  // (a handful of springs): update the last Cholesky factor by their rank-one terms instead of
  // refactorising, when that is cheaper (forward/low_rank_change.hpp, sparse_system.hpp), with
  // each solution checked against the pass's own system. The answers are those of a
  // refactorisation to round-off; false refactorises every pass (the reference).
  bool update_factorization = true;

  // --- Substep solver (forward/substep/) ---
  // time.substeps: velocity-level substeps per step. Each substep integrates velocities,
  // makes one biased sweep over the contacts, moves the blocks and makes one relax sweep
  // (Box2D v3's soft step); more substeps make stacks stiffer and contacts more accurate.
  int substeps = 4;

  // control.contact_passes: most passes over each manifold's points per sweep, stopping
  // when a pass changes no impulse by more than 1e-2 of the manifold's largest normal
  // impulse (forward/substep/solve_contacts.cpp). One pass (model revision 2026-11-25.3 and
  // before) leaves the coupling of a manifold's normal and friction impulses through the
  // block's rotation unconverged at an impact: a block landing on a 2:1 slope of friction
  // 25 deg kept 4.2 mm/s of the slip the landing's friction should have taken, and landings
  // near the friction angle ran up to 1.7 cm long in 1 s (docs/theory.md §13). With 16 the
  // landing sweep of tests/test_landing.cpp holds 5e-5 m (worst 3.3e-6); 8 missed one block
  // by 2.6e-4 m. Cost: 3 % on a standing wall, ~45 % on Vajont section I, ~60 % on
  // section VII; 2-8 passes cost as much and land fewer blocks right (docs/performance.md).
  int contact_passes = 16;

  // control.quiet_start_steps: most steps of the quiet start, in which the contacts touching at
  // t = 0 take up the weight from rest before the clock runs (forward/substep/quiet_start.cpp;
  // it stops sooner once no normal impulse changes by more than 1e-4 of the largest over a
  // step). A slope not in equilibrium never gets there, so a landslide runs them all: on Vajont
  // section I the change fell to 0.4 % within 100 steps, on section VII to about 10 % within
  // 50, and neither improved later. Section IV released after 100 bounced (at an earlier
  // revision), after 300 it ran; 0 starts the dynamics with unloaded contacts. The Vajont
  // scene sets 250: its sections I-VII ran within 0.40-0.93 % overlap and section VII's quiet
  // start took half its 14 s (docs/performance.md, "The quiet start's length").
  int quiet_start_steps = 500;

  // control.deep_overlap_ratio: the overlap, as a share of the smaller block of a pair, from
  // which the substep solver corrects a point in position and gives its blocks extra sweeps
  // (solve_contacts.hpp: converge_deep, correct_positions). Below it an overlap is left to the
  // push-out sweep, which under a much heavier block converges slowly at coarse steps: a
  // lighter block carrying a slider stays about this deep in its support, and the slider rides
  // tilted on it, its friction along the slope lowered by the tilt x (1 + tan^2 phi) (docs/
  // theory.md, Known limits (j)). 0 (the default) = automatic: kDeepOverlapSmallScene below
  // kAutoSubstepBlocks free blocks, kDeepOverlapLargeScene from there up.
  double deep_overlap_ratio = 0.0;

  // control.sleep_time, s: a group of touching blocks at rest this long sleeps (no sweeps,
  // no integration) until a moving block comes within the contact margin (forward/substep/
  // sleep.hpp; Box2D's islands). 0 (the default) never sleeps, the reference every published
  // number was made with. Once every free block sleeps, nothing can move again (no load
  // changes, no block moves to wake one), and the run records the rest of its time at once.
  double sleep_time = 0.0;
  // control.sleep_speed, m/s: at rest means every vertex of the block slower than this. 0 (the
  // default) means 1 % of rest_speed. Box2D sleeps bodies under 5 cm/s; a Vajont mass whose
  // measured points have stopped still moves at 0.1-10 mm/s there, and some of its blocks
  // faster (docs/performance.md).
  double sleep_speed = 0.0;

  // Soft contact constraint: stiffness as a frequency, Hz, and damping ratio. 0 Hz means
  // automatic: an eighth of the substep rate, Box2D's ratio (Box2D also caps it at 30 Hz
  // for games; at 30 Hz a stack of five 1 m blocks sank 1 cm; at a quarter of the rate a
  // heavy block on a light one, mass ratio 100, rocked itself up).
  double contact_hertz = 0.0;
  double contact_damping_ratio = 10.0;

  // control.split_impulses: how the substep solver pushes overlapping blocks apart
  // (docs/theory.md §13, "Split impulses"). true, the default since model revision
  // 2026-11-27.4: two sweeps of the velocities without push-out, then a sweep of push-out
  // velocities that move the blocks and are then dropped (Catto 2006, Bullet's split impulse),
  // so that no push-out is ever left as kinetic energy. false: Box2D v3's soft step (revision
  // .27.3 and before), a sweep whose velocities carry the push-out and a relax sweep that
  // takes it out again; an unconverged relax sweep leaves part of the push-out in the blocks:
  // a column of ten blocks at rest then creates energy (1 m blocks at 5 ms x 4; 8 m blocks at
  // 10 ms x 3) and Vajont section VII's resting mass rattles at 10 ms x 3 (0.41 m/s); with
  // split impulses both rest (tests/test_resting_column.cpp).
  bool split_impulses = true;

  // control.step_by_turn, substep solver. false (the default; the Vajont scene sets true): Shi's
  // rule for the blocks in contact, the step short enough that none of their vertices moves further
  // than the move limit (step_move_limit, block_system.hpp). true: the rule counts only the travel
  // a block's turning (and straining) gives its vertices; a block that slides further than the
  // limit widens its contacts' margin by the excess, as a block in flight always does
  // (speculative contact; docs/theory.md, "Step control"). A step's contact points are fixed on
  // its blocks, so turning moves them off the corners they stand for, and sliding does not. On
  // Vajont section VII degraded the toe's blocks, at 17-41 m/s against the opposite bank, cut
  // 1871 of the 45 s's 3115 steps to 8-12 ms; by turn the run took 2258 steps, worst overlap
  // 0.62 % (0.63 % by the whole travel). With no rule at all for the blocks in contact, section VI
  // overlapped by 1.08 % (docs/performance.md, "The step the blocks in contact choose").
  bool step_by_turn = false;

  // Substep solver: every block rigid (its three strain unknowns dropped; an elastic
  // material can ask for rigid blocks with materials.NAME.rigid). On by default: the
  // strain of a rock block in a slide is below 1e-3, and the substep solver's elastic
  // option (false: each block's stress relaxes towards the mean stress of its contacts,
  // forward/substep/block_stress.hpp) turned the impulses of impacts into strains of
  // several percent on Vajont section I. The implicit solver always keeps all six.
  bool rigid_blocks = true;

  // Worker threads for the substep solver's sweeps (graph-coloured, so 1 and N threads
  // give the same numbers bit for bit). 0 = what the caller set for OpenMP. Not a scene
  // key: set by the command line (--threads).
  int threads = 0;

  // Ensemble realisation (forward/perturb.hpp): 0 runs the scene as given; k >= 1 first
  // shifts every free block rigidly by a random offset of at most 1e-4 of its size, the
  // same offsets for the same k on any machine. Not a scene key: set by --ensemble and by
  // studies' ensembles.
  int realisation = 0;
  // The largest nudge of realisation k >= 1, as a fraction of a block's size; 0 = the
  // default, kJitterRatio (forward/perturb.hpp). Not a scene key.
  double jitter_ratio = 0.0;
};

// Returns an empty string when the options are usable, else "key: problem".
std::string validate_options(const SimulationOptions& options);

}  // namespace ddafit
