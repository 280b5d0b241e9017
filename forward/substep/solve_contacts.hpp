// Stage 4 of a substep-solver step, run in every substep: the contact impulses. The
// sweeps follow Box2D v3's soft step (Catto, "Solver2D"): warm start with the impulses of
// the last substep, one sweep with a soft push-out of overlaps, and, after the blocks
// have moved, one relax sweep without it so that no push-out velocity is kept.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/list_groups.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

// The push-out of an overlap as a spring of `hertz` and damping ratio `zeta` resolved
// over a substep h (after Box2D's b2Softness): with w = 2 pi hertz, a1 = 2 zeta + h w,
// a2 = h w a1, the push-out velocity is bias_rate x overlap and the impulse that makes it
// is scaled by mass_scale. (Box2D also relaxes the impulse towards zero; ddafit does not,
// solve_contacts.cpp says why.)
struct ContactSoftness {
  double bias_rate = 0.0;   // 1/s: w / a1
  double mass_scale = 1.0;  // a2 / (1 + a2)
};
ContactSoftness make_softness(double hertz, double zeta, double h);

struct SweepSettings {
  double h = 0.0;                 // substep, s
  ContactSoftness softness;
  double max_pushout_speed = 0.0;  // m/s: an overlap is pushed out no faster than this
  double linear_slop = 0.0;        // m: overlap tolerated without push-out (stops jitter)
  bool use_bias = true;            // false in the relax sweep
  int manifold_passes = 1;         // most passes over a manifold's points per sweep (control.contact_passes)
};

// Each block's manifolds (compressed rows: manifolds of block b are ids[first[b] .. first[b + 1])).
struct BlockManifolds {
  std::vector<int> first, ids;
  BlockManifolds(const std::vector<ContactManifold>& manifolds, size_t blocks);
};

// The blocks' rigid-body velocities (vx, vy, w) that the sweeps change, and their moves
// (dx, dy, dtheta) since the start of the step, from which each point's current gap
// follows without new geometry.
struct SweepState {
  std::vector<Vec3> velocity;
  std::vector<Vec3> step_moves;
  std::vector<BlockMass> masses;
  std::vector<Vec3> load_acceleration;  // per block, from loads other than gravity (water); empty if none
  std::vector<Vec3> free_velocity;  // per block: the substep's velocity before any contact impulse
  std::vector<Vec3> push_velocity;  // per block: this substep's push-out (control.split_impulses)
  // Per manifold: its two blocks (block_a, block_b), set by prepare_contacts. The loops that
  // scan every manifold for its blocks read this 8-byte pair, not a 576-byte ContactManifold.
  std::vector<std::array<int, 2>> pair_blocks;
  std::vector<char> deep;  // per manifold: a point overlapped beyond its deep_overlap in a relax sweep of the step
  std::vector<char> overlapping;  // per manifold: a point overlaps beyond the slop (push_out_overlaps' scratch)
  // Built when first needed in a step and kept for its substeps and its position correction
  // (the manifolds do not change within a step); reset with `deep` at the step's start.
  std::optional<BlockManifolds> of_block;
  // The manifolds of blocks beside a much heavier one (converge_heavy.hpp), in groups that share
  // no moving block (list_groups.hpp), built when first needed in a step; reset with of_block.
  std::optional<ListGroups> heavy;
  // Per block: substeps left in which its manifolds are held to a share of the impact margins
  // after a group solved for an impact took it in, or a weight-bearing joint of it was struck
  // (converge_impacts.cpp: kSettleShare, mark_struck). Kept
  // from step to step: a block's index does not change within a run.
  std::vector<int> settling_substeps;
  // Per block: taken into a group solved for an impact this substep while not settling
  // already (converge_impacts.cpp); the next warm start hands on only the impulses its points
  // carried into the impact, and clears it.
  std::vector<char> struck_now;
  // False when no interface of the scene has cohesion or tensile strength (run_substep.cpp): no
  // point can then carry tension, and the warm start skips cap_carried_tension.
  bool bonds = true;
  // This step's vertex-vertex points apart at detection: (manifold, gap then), m
  // (refresh_corner_gaps.hpp).
  std::vector<std::pair<int, double>> corner_points;
};

// st.pair_blocks, filled from `manifolds` when prepare_contacts has not (a state built by hand).
const std::vector<std::array<int, 2>>& pair_blocks(const std::vector<ContactManifold>& manifolds, SweepState& st);

// The manifolds, in order, with a moving block that `marked` (per block) flags: the
// neighbourhoods of converge_deep, correct_positions and converge_heavy.
std::vector<int> manifolds_of_blocks(const std::vector<std::array<int, 2>>& pairs, const std::vector<char>& marked,
                                     const std::vector<BlockMass>& masses);

// The manifolds flagged deep (SweepState::deep) and every other manifold of their moving blocks,
// in order; `involved` flags those blocks. converge_deep's and correct_positions' list.
std::vector<int> deep_neighbourhood(const std::vector<ContactManifold>& manifolds, SweepState& st,
                                    std::vector<char>& involved);

// st.of_block, built from `manifolds` if this step has not built it yet.
const BlockManifolds& block_manifolds(const std::vector<ContactManifold>& manifolds, SweepState& st);

// Applies impulse P (a vector) at the point: -P on block a, +P on block b.
inline void apply_impulse(Vec3& va, Vec3& vb, const BlockMass& ma, const BlockMass& mb, const ContactPoint& p,
                          const Vec2& impulse) {
  va[0] -= ma.inverse_mass * impulse.x();
  va[1] -= ma.inverse_mass * impulse.y();
  va[2] -= ma.inverse_inertia * cross2(p.ra, impulse);
  vb[0] += mb.inverse_mass * impulse.x();
  vb[1] += mb.inverse_mass * impulse.y();
  vb[2] += mb.inverse_inertia * cross2(p.rb, impulse);
}

// One manifold of a sweep: passes over its points until they agree (control.contact_passes).
// Sets `deep` when a relax pass finds a point overlapping beyond its deep_overlap.
void solve_manifold(ContactManifold& m, char& deep, const SweepSettings& settings, double inv_h, SweepState& st);

// Applies each point's accumulated impulses of the last substep to its blocks (warm start), as
// the starting guess of this substep's sweeps; a persisting load is then met at once. An
// impact's impulse does not persist: the blow is over once the blocks are stopped. At the
// manifolds of a block struck in the last substep (SweepState::struck_now) each point hands on
// at most the normal impulse it carried into that substep (its resting share), with its
// friction scaled by the same factor, so still within Mohr-Coulomb. Re-applied whole, the
// impact's impulses threw a column back up: a 1 m block dropped at 5 m/s onto twenty 0.25 m
// blocks came back at 49 % of its speed (its group had stopped it and the column), 15 of 48
// drops onto columns of 20 and 30 beyond their bound (model revision 2026-11-29.4;
// tests/test_impact_rebound.cpp). Only the first substep after the blow: capped at every
// substep of the settling that follows, the hand-on ratchets down below the weight and the
// column rocks (a 1 m block at 0.4 m/s onto fifteen 0.25 m blocks at 45 deg: 34 %, bound 30 %).
// Handing on nothing at all stopped the columns as well, but left Vajont section VIII
// degraded's sliding mass unsupported after each impact (overlap 1.7 %, twice the wall).
void warm_start(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                SweepState& state);

// A point's impulse over a substep is the contact force times h, so the warm start hands on a
// force: when the substep's length changes from one step to the next (the step control
// shortens a step where a block in contact would move too far, and a step is cut short to
// land on an output time), every carried impulse is scaled by ratio = h_new / h_old, Box2D
// v2's dtRatio (model revision 2026-12-03.6). Unscaled, a 0.6 ms step landing on an output
// after a 9.4 ms one warm-started with 16 times the load, and its sweeps, taking that back,
// kicked the blocks of a slab against each other: a 2 x 2 slab over joints at -55 deg fell
// 1.46 % off seed Eq. 4 (10 ms x 3; 1e-4 scaled; StackedSliderStepLengths). Sleeping
// manifolds are scaled too: the product of the ratios is the ratio since they slept.
// prepare_contacts applies it in its pass over the points (ratio 1 before the first step).
inline void rescale_warm_start(ImpulseState& impulse, double ratio) {
  impulse.normal *= ratio;
  impulse.tangent *= ratio;
  impulse.carried *= ratio;  // what the last warm start applied: the blow test compares it with `normal`
}
void solve_contacts(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                    const SweepSettings& settings, SweepState& state);

// Split impulses (control.split_impulses; Catto 2006, Bullet's split impulse): after the
// velocity sweeps, which push nothing out, one sweep over push-out velocities of their own,
// starting from zero each substep. At a point overlapping beyond the slop its normal push-out
// velocity becomes bias_rate x the excess (at most max_pushout_speed), with a push-out impulse
// that never pulls. The blocks then move by h x these velocities as well (integrate.hpp) and
// the velocities are dropped: a push-out moves blocks, it never speeds them up.
void push_out_overlaps(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                       const SweepSettings& settings, SweepState& state);

// Split impulses' velocity sweeps run before the substep's move, so the gap they see is the
// substep's start and they cannot flag a point that the move will take deep. This flags it
// ahead: a point whose gap after a move of h at its present closing speed would pass its
// deep_overlap. An impact into a chain of blocks (Vajont section VII degraded: a 9 m block
// at 25 m/s into a 2 m one, still closing at 15 m/s after the sweeps) is then converged by
// converge_deep before the move, not after it.
void flag_closing_deep(const std::vector<ContactManifold>& manifolds, double h, SweepState& state);

// After a relax sweep: `iterations` more relax sweeps, on one thread and in order, over the
// manifolds flagged deep (a point overlapping beyond its deep_overlap) and the other
// manifolds of their blocks. One sweep per substep leaves the impulses of a light block
// squeezed between heavy ones far from converged (Gauss-Seidel loses ~10 % of the error per
// sweep at a mass ratio of 20): on Vajont section VIII a 1.7 m block was still being closed
// on at 13 m/s and sank 5 % of its size. These few manifolds get the iterations they need,
// the thousands of others the one sweep that suffices for them.
// With closing_h > 0 (split impulses, the substep's length): the sweeps also move the blocks
// on the far side of the listed manifolds, whose other manifolds are not listed. A far block
// that they would now carry deep (flag_closing_deep's test) joins the list with all its
// manifolds, and the sweeps run again, for up to four rounds. Without it, on Vajont section
// X reference (revision .27.6) the sweeps drove a 1.8 m block into its neighbour at 13 m/s,
// 1.02 % of its size within a substep, the neighbour's contact untouched.
void converge_deep(std::vector<ContactManifold>& manifolds, const SweepSettings& relax, int iterations,
                   SweepState& state, double closing_h = 0.0);

// Position correction, once per step after the substeps (Box2D v2's non-linear Gauss-Seidel
// position pass, kept for deep overlaps only): every point of a manifold that a relax sweep of
// the step found overlapping by more than its deep_overlap (prepare_contacts.hpp) moves its two
// blocks apart along its normal by `fraction` of the excess over that depth, at most
// `max_correction` (m) per pass, straight in position (the step's moves) and not through
// velocities, so that no push-out speed is left as kinetic energy. The soft push-out of the
// sweeps alone left overlaps of 1.5-3 % of a block in Vajont's flowing mass, where a small
// block squeezed between two large ones converging at 4 m/s is pushed out slower than they
// close: a sandwich of a light block is where Gauss-Seidel converges slowest. The passes run
// over those manifolds only (a few per step), in order, on one thread.
struct PositionCorrection {
  int passes = 0;
  int extra_passes = 0;  // more passes, taken only while the last pass still corrected something
  double fraction = 0.0;
  double max_correction = 0.0;  // m
};
void correct_positions(const std::vector<ContactManifold>& manifolds, const PositionCorrection& settings,
                       SweepState& state);

// After a substep moved the blocks by `moves`: the slip of each closed point, gathered into
// its face's slip history (seed Eq. 2, forward/contact/slip_history.hpp), and the friction
// that follows; a bond is lost once its point has slid or opened at its strength by more
// than `tolerance` (contact_law.hpp, wear_bond).
void advance_slip(const BlockSystem& system, const std::vector<Vec3>& moves, double h, double tolerance,
                  ContactSet& contacts);

// Block b's rate (or move) relative to block a's at the point, along `direction`, from the two
// blocks' rates: velocities (vx, vy, w) or moves (dx, dy, dtheta).
inline double relative_rate(const Vec2& direction, const ContactPoint& p, const Vec3& rate_a, const Vec3& rate_b) {
  return direction.dot(velocity_at(rate_b, p.rb) - velocity_at(rate_a, p.ra));
}

// Block b's rate (or move) relative to block a's at the point, along the normal: > 0 opening.
// `rates` per block.
inline double normal_rate(const ContactManifold& m, const ContactPoint& p, const std::vector<Vec3>& rates) {
  return relative_rate(m.normal, p, rates[m.block_a], rates[m.block_b]);
}

// The gap of a point now: its gap at the start of the step plus the relative move of the
// two blocks at the point along the normal.
inline double current_gap(const ContactManifold& m, const ContactPoint& p, const std::vector<Vec3>& step_moves) {
  return p.separation + normal_rate(m, p, step_moves);
}

}  // namespace ddafit
