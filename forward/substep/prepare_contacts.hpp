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
// Every carried impulse is scaled by `warm_ratio`, this substep's length over the last one's
// (rescale_warm_start, solve_contacts.hpp; 1 keeps them). On ctx.contacts, with
// ctx.state.masses and the slop of ctx.detection.
void prepare_contacts(SubstepContext& ctx, double h, double deep_overlap, double warm_ratio);

constexpr int kSerialColour = 63;

// Groups manifolds into colours such that no two manifolds of a colour share a moving
// block (Box2D v3's constraint graph): a colour's manifolds can be solved at the same
// time, in any order, and give the same numbers on any number of threads. Colours are
// tracked per block in one 64-bit mask; manifolds that find none free go to colour
// kSerialColour, which is solved serially.
//
// Greedy, from the lowest manifold up: in order of the height of their points along `up`
// (against gravity; ties and a zero `up` keep the manifolds' order), so that the sweeps meet
// the contacts that carry a weight before those that load them (the contact graph ordered
// by height of Guendelman, Bridson & Fedkiw 2003, "Nonconvex rigid bodies with stacking").
// Model revision 2026-12-02.3. Until then the order was the manifolds' own (by piece pair,
// that is by the order of the scene's blocks), and Gauss-Seidel's answer depended on it
// (docs/theory.md §13, "Limits of the substep solver"): a rigid plank over many short
// joints swung in a two-cycle between its sweeps and ran 3.0 % (mirrored 3.8 %) ahead of
// seed Eq. 4, and a column of ten 16 m blocks listed from the top down did not come to rest.
std::vector<std::vector<int>> colour_manifolds(const BlockSystem& system,
                                               const std::vector<ContactManifold>& manifolds, const Vec2& up);

// The ids 0..n-1 ordered by key, ties in id order: the order std::stable_sort gives, found by
// an LSD radix sort over the keys' bits in linear time (-0.0 ties with 0.0; no NaN keys).
// colour_manifolds orders some 20 000 manifolds of Vajont section VII this way every step;
// the comparison sort took about 3.5 s of the run's 95 s (docs/performance.md).
void order_by_key(const std::vector<double>& key, std::vector<int>& order);

}  // namespace ddafit
