// Stage 3 of a substep-solver step: everything the substeps reuse. Each block's inverse
// mass and inertia, each contact point's lever arms and effective masses, and the
// colouring of the manifolds that lets the sweeps run in parallel.
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/substep_context.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

// Inverse mass and inertia per block (substep_types.hpp, BlockMass).
void compute_block_masses(const BlockSystem& system, std::vector<BlockMass>& masses);

// Effective masses of every point, at the start of the step; bonded points get their
// cohesion and tension as impulses over one substep h (contact_law.hpp); each manifold the
// overlap from which its points are corrected in position: `deep_overlap` times the smaller
// free block's size (the square root of its area), at least the slop (solve_contacts.hpp).
// On ctx.contacts, with ctx.state.masses and the slop of ctx.detection.
void prepare_contacts(SubstepContext& ctx, double h, double deep_overlap);

// Groups manifolds into colours such that no two manifolds of a colour share a moving
// block (Box2D v3's constraint graph): a colour's manifolds can be solved at the same
// time, in any order, and give the same numbers on any number of threads. Greedy, in
// manifold order. Colours are tracked per block in one 64-bit mask; manifolds that find
// none free go to colour kSerialColour, which is solved serially.
constexpr int kSerialColour = 63;
std::vector<std::vector<int>> colour_manifolds(const BlockSystem& system,
                                               const std::vector<ContactManifold>& manifolds);

}  // namespace ddafit
