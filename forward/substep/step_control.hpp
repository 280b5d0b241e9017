// The substep solver's step control (stage 1 of its step): which blocks are near a
// contact, the step their speed allows, how far beyond the contact margin a fast block in
// flight can reach, and how far a block in contact moved (the check that the margin held).
#pragma once

#include "forward/substep/substep_context.hpp"

namespace ddafit {

// Which blocks have a contact point within the scene's contact margin (not the widened one).
void mark_near(SubstepContext& w);

// The next step: the scene's, grown back by the growth factor after a shorter one, and
// short enough that no vertex of a block in contact moves further than allowed, counting
// the speed gravity adds within the step (the contact margin covers that distance); with
// control.step_by_turn, the travel that turning gives them. Also sets each block's reach (w.reach).
double choose_step(SubstepContext& w, double previous);

// Per block, how much further than max_move its vertices can travel in a step of dt: the
// speculative margin its contacts get on top of the scene's (w.extra_reach).
void speculative_reach(SubstepContext& w, double dt);

// Largest distance a vertex of a block in contact moved in the step.
double largest_move(const SubstepContext& w);

}  // namespace ddafit
