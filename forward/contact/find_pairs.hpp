// Stage 1 of a step, both solvers: the broad phase. Which convex pieces of different
// blocks are close enough to touch within the step.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// Splits every block into convex pieces (forward/contact/convex_pieces.hpp), once per run.
// Returns an empty string, or the name of a block that could not be split.
std::string build_shapes(const BlockSystem& system, ContactShapes& shapes);

// Pairs (a, b), a < b, of pieces of different blocks, not both fixed, whose bounding boxes
// grown by `margin`, and each by its block's `extra_reach` (m, per block; empty for none),
// overlap: sort and sweep along x, O(n log n) in the pieces. The pairs come out sorted, so
// the contacts built from them are in the same order on every run.
std::vector<std::pair<int, int>> find_pairs(const BlockSystem& system, const ContactShapes& shapes,
                                            double margin, std::span<const double> extra_reach = {});

}  // namespace ddafit
