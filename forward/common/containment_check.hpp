// A block that passes into a fixed block (the bedrock, the opposite bank) is lost: once
// inside, no contact holds it, and it falls through the model. Neither the energy audit (it
// gains no energy) nor the overlap check (no contact is left to measure) sees that, so the
// run checks it directly: no free block's centroid may lie inside a fixed block.
#pragma once

#include <string>

#include "forward/block_system.hpp"

namespace ddafit {

// Empty when every free block is outside every fixed block, else a diagnosis naming the
// block, where it is and what to change. A concave free block whose centroid lies outside
// its own outline (an L wrapped round a corner of the bedrock) is not judged by its
// centroid and is skipped.
std::string check_containment(const BlockSystem& system);

}  // namespace ddafit
