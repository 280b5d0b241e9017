// A block that passes into a fixed block (the bedrock, the opposite bank) is lost: once
// inside, no contact holds it, and it falls through the model. Neither the energy audit (it
// gains no energy) nor the overlap check (no contact is left to measure) sees that, so the
// run checks it directly: no free block's centroid may lie inside a fixed block, and none may
// have passed through one within the step (a step long enough to carry a block from one side
// of a fixed block to the other leaves no overlap to see at its end).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "forward/block_system.hpp"

namespace ddafit {

// Every block's centroid at the start of a step (fixed blocks too, so ids index it), for
// check_containment's test of the path within the step, and each free block's inradius about
// its centroid, taken once from the first step's geometry (it only decides which blocks moved
// far enough to be tested, and strain changes it by parts in 1e4).
struct StepStart {
  std::vector<Vec2> centroid;
  std::vector<double> inradius;
};
void remember_step_start(const BlockSystem& system, StepStart& start);

// Empty when every free block is outside every fixed block, else a diagnosis naming the
// block, where it is and what to change. A concave free block whose centroid lies outside
// its own outline (an L wrapped round a corner of the bedrock) is not judged by its
// centroid and is skipped. With `step_start` (remember_step_start before the step), a block
// whose centroid moved along a straight path through a fixed block's interior is lost too;
// only blocks that moved by a quarter of their inradius or more are tested, since a centroid
// that starts outside a fixed block with no deeper overlap cannot reach it in a shorter move.
std::string check_containment(const BlockSystem& system, const StepStart* step_start = nullptr);

}  // namespace ddafit
