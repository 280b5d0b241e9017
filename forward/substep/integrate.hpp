// The integration stages of the substep solver (Box2D v3's soft step keeps them apart
// from the contact sweeps).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

// The water's load on every free block as accelerations (force / m, moment / I), taken
// half the step `dt` ahead of the step's start (forward/water/hydrostatic.hpp, the
// leapfrog); clears them in a dry scene. The
// strain terms of the load are left to the block stress (block_stress.hpp), which takes
// its stress from the contacts only.
void water_accelerations(const BlockSystem& system, double gravity, double dt, SweepState& state);

// v1 = v0 + h (g + a_load) on every moving block (the strain unknowns carry no inertia,
// substep_types.hpp; a uniform body force has no moment about the centroid). Keeps v0 in
// `start_velocity` for the position update.
void integrate_velocities(SweepState& state, const Vec2& gravity, double h, std::vector<Vec3>& start_velocity);

// The move of each block over the substep, d = h (v0 + v1) / 2: the trapezoidal rule
// integrates free flight and steady sliding exactly (a symplectic x += h v1 would lag by
// a h^2 / 2 per substep). Writes d to `moves` and adds it to the state's step moves.
// With smooth_acceleration >= 0 (split impulses), d = h v1 - h dv / 2, where dv = v1 - v0
// capped at h x smooth_acceleration (plus twice the block's water load; the turn through
// the radius of gyration): the trapezoid for changes that steady forces make, the velocity
// after an impact for the rest. An impact's trapezoid moves the block by h |v0| / 2 into
// the contact that stopped it: on Vajont section VII a block rotating into its neighbour
// at 14 m/s went 2 cm deep in one substep. Without gravity (smooth_acceleration 0) every
// change is an impact's and d = h v1, which is exact for free flight there too.
void integrate_positions(SweepState& state, double h, const std::vector<Vec3>& start_velocity,
                         std::vector<Vec3>& moves, double smooth_acceleration = -1.0);

// Split impulses (control.split_impulses): each block also moves by h x its push-out velocity
// (solve_contacts.hpp, push_out_overlaps), which is not kept.
void add_push_out_moves(SweepState& state, double h, std::vector<Vec3>& moves);

// At the end of the step: moves every block by its step move with the exact rotation
// about its centroid. Turns about the centroid and translations compose exactly, so one
// move per step equals the substeps' moves in sequence. Sets the blocks' rates to the
// sweeps' velocities (no strain rate). `measured` false (the quiet start) moves the
// measurement points' origins with them.
void move_blocks(BlockSystem& system, const SweepState& state, bool measured);

}  // namespace ddafit
