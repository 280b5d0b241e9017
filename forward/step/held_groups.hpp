// Groups of the settling before t = 0 that friction holds (settle_sliding.hpp, model revisions
// 2026-12-06.9 to .12): which stop, and whether a hold is one friction can give.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "forward/step/sliding_groups.hpp"

namespace ddafit {

// Groups whose net force points against their slip, friction at the caps of their sliding points
// holding more than pulls them, do not slide: the lower block of a weaker joint, whose face the
// locked settling overloaded with the upper block's weight too (a 35 deg face at 30 deg under a
// joint at 20 deg: g sin a + g cos a tan phi_j < 2 g cos a tan phi_b). Their sliding points on the
// side their slip was read from lock at the force they carry. A group that slipped against the
// ground is held for the rest of the stage; one that slipped against another group joins it
// through the locked points (a block riding on a sliding block).
//
// Returns whether any group stopped. Whether friction can give the hold is holds_within_caps'.
bool hold_stopped_groups(const BlockSystem& s, const SlidingGroups& g, const std::vector<Vec6>& velocities,
                         const Eigen::VectorXd& f, ContactSet& contacts, std::vector<char>& held);

// Whether every held block can be held by friction: the shear its faces against the ground carry,
// |sum T|, within their caps, tan(phi) N' + c l, with N' the normal load the block brings to
// them, its weight across the face and what the blocks resting on it press on it. Not the
// springs' own N: a tall slider 1 deg steeper than its friction (r = 0.9, 3 m long) was settled
// with its front points carrying 1.19 times its weight across the face, so its spring caps held
// it; left as the first settling had it, as before revision 2026-12-06.11 (4 of the 216 tall
// sliders of tests/test_tall_sliders.cpp ran off seed Eq. 4 otherwise).
bool holds_within_caps(const BlockSystem& s, const ContactSet& contacts, const std::vector<char>& settled,
                       const std::vector<char>& held, const Vec2& gravity, double shear_penalty);

}  // namespace ddafit
