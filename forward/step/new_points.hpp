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

#include <vector>

namespace ddafit {

// The tangential speed of block b against block a at point p of manifold m (m/s):
// m.tangent . (T_b(p) V_b - T_a(p) V_a).
double relative_slide(const BlockSystem& system, const ContactManifold& m, const ContactPoint& p);

// `slip_tolerance` (m): a relative tangential motion over the step `dt` below this is no slide.
void start_new_points(const BlockSystem& system, ContactSet& contacts, double dt, double slip_tolerance);

// Stage 1d, after the impacts are resolved (resolve_impacts.hpp): a locked point of a free
// block an impact has struck (`struck`, per block: in an impact group this step) whose blocks
// now slide past each other by more than `slip_tolerance` (m over the step dt) starts the
// step sliding the way it moves, with the friction of the normal force it carried
// (N tan(phi)). Left locked, its shear spring meets the whole slip of the step (4 cm for a row
// struck to 4 m/s at 10 ms): the first iterate's spring forces, a hundred times the blocks'
// weight, pressed the row into the floor, and that normal force, as friction, stopped the row
// within the step (tests/test_impact_rows.cpp, free rows: in one step the floor took 1.8
// times the row's momentum, where its friction could take 1.4 %). Bonded points stay locked.
// `shear_penalty`, N/m, pre-loads the spring at the friction force, as update_blocks does for
// every sliding point. (Withdrawn at revision 2026-11-28.2, when it tipped the implicit Vajont
// section I run over an energy audit that misread strain as potential energy; back at .28.4.)
void start_impact_slides(const BlockSystem& system, ContactSet& contacts, const std::vector<char>& struck,
                         double dt, double slip_tolerance, double shear_penalty);

}  // namespace ddafit
