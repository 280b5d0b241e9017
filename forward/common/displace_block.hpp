// Moving a block by its six unknowns, for both solvers: the exact map of Shi's first-order
// displacement (rotation by the angle, not its tangent; docs/theory.md), applied to the
// block's vertices and measurement points, with the strain's stress added.
#pragma once

#include "forward/block_system.hpp"

namespace ddafit {

// Largest displacement of a vertex of block b for its unknowns db.
double block_displacement(const BlockSystem& system, int b, const Vec6& db);

// Moves block b and its material points by db (exact rotation), adds the strain's
// stress and refreshes the block's geometry. When the motion is not part of the
// measured history (settling), the points' origins move with them.
void displace_block(BlockSystem& system, int b, const Vec6& db, bool measured);

}  // namespace ddafit
