// The deepest overlap of a run, as both solvers report it (summary.json,
// solver.worst_penetration_ratio): the depth of a contact point's overlap relative to the
// smaller free block of its pair (the square root of its area; a fixed block, such as the
// bedrock, does not count).
#pragma once

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

struct WorstOverlap {
  double depth = 0.0;  // m
  double ratio = 0.0;  // depth / the smaller free block's size
  double time = 0.0;   // s
  int block_a = -1, block_b = -1;

  // Keeps `depth` (m, > 0 = overlap) of a point of manifold m at `time` if it is the
  // worst so far.
  void note(const BlockSystem& system, const ContactManifold& m, double depth, double time);
};

}  // namespace ddafit
