// Stage 1b of a step, after the contacts are found: the springs of the points that appeared
// in this step. A new point where the blocks already slide past each other (a block's corner
// passing the edge it pivots on, a block crossing onto the next) starts sliding, with no
// friction until the open-close iteration has given it a normal force. Started locked, its
// shear spring would grab the block at the full slip of the step (1.3 mm at 1.3 m/s and
// 1 ms), pitch it onto the point, and the normal force of that iterate, fifty times the
// block's weight, became a sliding friction that stopped a 1 m block in one step
// (test_joint_crossing.cpp, the step down).
#pragma once

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// The tangential speed of block b against block a at point p of manifold m (m/s):
// m.tangent . (T_b(p) V_b - T_a(p) V_a).
double relative_slide(const BlockSystem& system, const ContactManifold& m, const ContactPoint& p);

// `slip_tolerance` (m): a relative tangential motion over the step `dt` below this is no slide.
void start_new_points(const BlockSystem& system, ContactSet& contacts, double dt, double slip_tolerance);

}  // namespace ddafit
