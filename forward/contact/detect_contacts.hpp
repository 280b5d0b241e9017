// Stages 1-2 of a step, both solvers: the broad phase (find_pairs.hpp) and the narrow
// phase (collide.hpp) over the convex pieces of the blocks, built once per run.
#pragma once

#include <string>

#include "forward/block_system.hpp"
#include "forward/contact/collide.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

// Splits the blocks into convex pieces. Returns an empty string, or the name of a block
// that could not be split.
std::string prepare_detection(const BlockSystem& system, ContactDetection& detection);

// Replaces `contacts` with this step's, carrying state over (collide.hpp). Returns an
// empty string, or a description of two touching blocks that have no interface.
std::string detect_contacts(const BlockSystem& system, ContactDetection& detection, ContactSet& contacts);

}  // namespace ddafit
