// Stage 5 of a step, once it is accepted: move the blocks (exact rotation), carry the
// velocities and stresses forward, and advance the contacts' slip and shear springs.
#pragma once

#include "forward/step/implicit_context.hpp"

namespace ddafit {

// Moves the blocks and advances every point's spring: a locked point keeps its shear
// offset, a sliding one slips (seed Eq. 2, into its face's slip history) and its shear
// spring trails it at the friction force, an open one lets go; bonds are lost once a
// point slides or opens (forward/contact/contact_law.hpp). D is ctx.equations.d of the
// accepted attempt; the shear springs are at the current penalty (ctx.control).
void update_blocks(ImplicitStepContext& ctx, double time_step);

// A block's velocity at the end of a step of length dt with unknowns d (6), from its
// velocity at the start (b.velocity); `gravity` is |g|, m/s^2. Used by update_blocks and by
// the step's energy judgement (judge_step.cpp), so both read the same velocities.
Vec6 step_velocity(const Block& b, const Vec6& d, double dt, double gravity);

}  // namespace ddafit
