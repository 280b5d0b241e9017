// Which free blocks rest on the ground at t = 0: joined to a fixed block through contacts
// that touch (separation within the slop), directly or through other touching free blocks.
// Both solvers' starts (step/settle_contacts.cpp, substep/run_substep.cpp quiet_start) settle
// only these: a cluster of blocks touching one another in flight is not resting on anything,
// and settling it drops it. Until revision 2026-11-29.3 "touching anything" was the rule: a
// row of 24 blocks side by side, given 3 m/s 0.3 m above a row at rest, was dropped 0.43 m
// into that row by the implicit solver's settling passes (a pass moves a block up to ten
// steps' displacement, 0.7 m there), and the first step could not push it out
// (tests/test_crushed_sliver.cpp).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// One entry per block: 1 for a free block resting on the ground as above, 0 otherwise
// (fixed blocks included).
std::vector<char> supported_blocks(const BlockSystem& s, const std::vector<ContactManifold>& manifolds, double slop);

}  // namespace ddafit
