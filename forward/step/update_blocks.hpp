// Stage 5 of a step, once it is accepted: move the blocks (exact rotation), carry the
// velocities and stresses forward, and advance the contacts' slip and shear springs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/common/displace_block.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/step/check_contacts.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/implicit_context.hpp"

namespace ddafit {

// Largest displacement of any vertex over the step for the solved unknowns d.
double max_vertex_displacement(const BlockSystem& system, const Eigen::VectorXd& d);

// Deepest penetration (> 0) among closed contacts that the step made deeper, and which
// contact it is. Depth counts from where the spring is unloaded (spring_reference), so
// a deep contact being pushed out is judged on what the step adds. A contact deeper than
// hard_limit in all reads as at least as deep as `limit` (the limit the caller compares
// against): a penalty too soft would otherwise let a block sink a little further every
// step, each step mending nothing.
double max_penetration(const ContactSet& contacts, const StepParameters& step, double limit, double hard_limit,
                       PointRef* which = nullptr);

// Moves the blocks and advances every point's spring: a locked point keeps its shear
// offset, a sliding one slips (seed Eq. 2, into its face's slip history) and its shear
// spring trails it at the friction force, an open one lets go; bonds are lost once a
// point slides or opens (forward/contact/contact_law.hpp). D is ctx.equations.d of the
// accepted attempt; the shear springs are at the current penalty (ctx.control).
void update_blocks(ImplicitStepContext& ctx, double time_step);

}  // namespace ddafit
