// The two integration stages of every substep (Box2D v3's soft step keeps them apart
// from the contact sweeps).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

// v1 = v0 + h g: gravity on the rigid-body unknowns (the strain ones carry no inertia,
// substep_types.hpp). Keeps v0 in `start_velocity` for the position update.
void integrate_velocities(BlockSystem& system, const std::vector<BlockMass>& masses, const Vec2& gravity, double h,
                          std::vector<Vec6>& start_velocity);

// Moves each block by d = h (v0 + v1) / 2 with the exact rotation: the trapezoidal rule
// integrates free flight and steady sliding exactly (a symplectic x += h v1 would lag by
// a h^2 / 2 per substep). Writes each block's d to `moves` and adds it to `step_moves`.
// `measured` false (the quiet start) moves the measurement points' origins with them.
void integrate_positions(BlockSystem& system, const std::vector<BlockMass>& masses, double h,
                         const std::vector<Vec6>& start_velocity, std::vector<Vec6>& moves,
                         std::vector<Vec6>& step_moves, bool measured = true);

}  // namespace ddafit
