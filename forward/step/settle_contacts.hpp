// Stage 0, before the first step: pre-load the contacts that touch at t = 0.
//
// A block laid on a slope starts with unloaded penalty springs. In the first dynamic
// step it drops into them and its normal force, hence its friction, is about half the
// static value: a downslope velocity error of ~2.5 mm/s that the seed's incline check
// would carry for the whole run (6 % of the displacement at 1 cm of travel). Shi's
// static step cures this: solve with inertia but zero velocity, move the blocks, keep
// their velocities, repeat. Each pass closes the gap to equilibrium by the factor
// (2M/dt^2) / (2M/dt^2 + K): the passes use a step kSettleStepScale times longer than
// the run's, which makes the inertia small beside the springs and the elastic blocks
// (the factor falls below 1e-2 for the incline check, and the pre-load converges).
// Only blocks that touch something move; blocks in flight are left exactly as given.
// A pass that would move a block more than `max_shift` is not applied: such a block is
// not near equilibrium (a block balanced on a corner), and the dynamics take over. A block
// that falls more slowly (a pass turns it about a point it rests on, further than the pass
// before or by more than a strain's worth) starts where it was given, with every free block
// touching it, and the rest settle again without them (settle_contacts.cpp: kFallingRatio,
// kPivotShare, kFallingTurn).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/detect_contacts.hpp"
#include "forward/step/implicit_context.hpp"
#include "forward/step/assemble.hpp"

namespace ddafit {

constexpr double kSettleStepScale = 30.0;
// ... and at least this many elastic periods L / c of the largest free block. At short steps
// thirty of them leave the inertia larger than the springs: a 200 x 50 m slider at 0.005 L/c
// (passes of 0.15 L/c) closed only 3.5 % of its distance to equilibrium per pass, which read as a block
// falling (kFallingRatio), and it started as given, unloaded, 73 % off seed Eq. 4 (model
// revision 2026-12-06.6). At one period the factor is about 0.1 for such a slider.
constexpr double kSettlePeriods = 1.0;

// Passes stop once no block moves by more than this fraction of max_shift. A tall
// elastic column converges slowly (factor 0.5 per pass for the 225 m Vajont mass): three
// fixed passes left 3 cm of settlement that the dynamics released as bouncing.
constexpr double kSettleTolerance = 1e-5;

// Runs at most `passes` passes, each followed by a new detection (`detection`, whose
// first_step stays set so that the contacts touching once settled bond). Returns false if
// the solver fails; `problem` names a pair of touching blocks without an interface.
// On ctx.system, ctx.detection and ctx.contacts, control.settle_passes passes at most.
bool settle_contacts(ImplicitStepContext& ctx, const StepParameters& step, double max_shift, std::string& problem);

// Loads the springs of the settled contacts: each point's normal force from its overlap, and
// points whose locked shear exceeds their Coulomb cap, or whose blocks are given a velocity
// along them, set sliding at the cap. Also used by settle_sliding.cpp after each of its passes.
void load_springs(const BlockSystem& s, ContactSet& contacts, const StepParameters& step);

// One settling pass applied (settle_contacts' passes, settle_sliding.cpp's): the blocks marked in
// `moves` move by their part of `d` (as settling, not measured motion), the locked points' shear
// offsets take up the slip, and the contacts are detected again with first_step set, so that new
// touching points lock. Returns the detection's problem, empty if none.
std::string apply_settling_pass(ImplicitStepContext& ctx, const Eigen::VectorXd& d, const std::vector<char>& moves);

}  // namespace ddafit
