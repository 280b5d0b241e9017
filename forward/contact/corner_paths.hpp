// Corners that pass each other: the vertex-vertex points of both solvers (model revision
// 2026-12-06.19).
#pragma once

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// A vertex-vertex point (manifold.hpp: two pieces apart whose closest features are two
// corners) has its normal along the line joining the corners, and both solvers take its gap
// as the gap at detection plus the pieces' relative move along that line. That is exact for
// corners heading at each other, but it closes as well for a corner passing the other: a block
// riding on a 5 mm thick slider crossed each joint of the ground with its front corner 5 mm
// above the joint's corner, the line between the corners slanted back, and the constraint
// along it threw the pair back and the rider up (5 cm blocks: 8-49 % short of seed Eq. 5 at
// 5-10 ms on both solvers; docs/theory.md §3, "Corners passing corners").
//
// Whether the corners of point p pass each other over `interval` s: each corner followed
// along its block's rate (vx, vy, w) relative to the other block, as a straight path, enters
// neither the other piece grown by `grow`. The pieces and corners are those at detection
// moved rigidly by `move_a` / `move_b` (the substep solver's moves so far; zero for the
// implicit solver, which moves its blocks once a step). `separation` is the point's gap at
// detection (the point lies midway between the corners).
bool corners_pass(const BlockSystem& s, const ContactShapes& shapes, const ContactManifold& m, const ContactPoint& p,
                  double separation, const Vec3& move_a, const Vec3& move_b, const Vec3& rate_a, const Vec3& rate_b,
                  double interval, double grow);

// Whether p is a vertex-vertex point of two pieces apart at detection.
bool apart_corners(const ContactManifold& m, const ContactPoint& p);

}  // namespace ddafit
