// Stage 2 of a substep-solver step: the narrow phase. One manifold per touching pair of
// convex pieces: one normal (the separating axis of the reference face), at most two
// points, a single point with the normal joining the corners when two corners meet
// (forward/substep/manifold.hpp). Points keep their impulses and slip from the last step.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

struct CollideSettings {
  double margin = 0.0;       // m: points are kept while their gap is below this (speculative)
  // m, per block (empty: none): a block moving further in the step than the margin covers
  // (a block in flight) widens the margin of its pairs by this much, so it cannot pass
  // through a neighbour unseen; overlaps deeper than `margin` alone are still not contacts.
  std::span<const double> extra_reach;
  double linear_slop = 0.0;  // m: tolerance of the separating-axis choice
  bool first_step = false;   // bonds (cohesion, tension) form only between blocks touching at t = 0
};

// Replaces `manifolds` (the last step's, sorted by piece pair) with this step's. Returns
// an empty string, or a description of two touching blocks that have no interface.
std::string collide(const BlockSystem& system, const SubstepShapes& shapes,
                    const std::vector<std::pair<int, int>>& pairs, const CollideSettings& settings,
                    std::vector<SubstepManifold>& manifolds);

}  // namespace ddafit
