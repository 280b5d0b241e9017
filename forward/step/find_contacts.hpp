// Stage 1 of a step: find vertex-edge contact candidates and carry over the state of
// contacts that existed in the previous step.
#pragma once

#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact.hpp"

namespace ddafit {

struct ContactSearch {
  double search_distance = 0.0;  // rho: candidates need |d_n| < rho (field notes: 2-2.5 x max step displacement)
  bool first_step = false;       // bonds (cohesion, tension) form only between blocks touching at t = 0
};

// Replaces `contacts` with the current candidates. Uses a uniform grid over edges, so
// the cost grows with the number of vertices, not with block pairs. Returns an empty
// string, or a description of a pair of touching blocks that has no interface.
std::string find_contacts(const BlockSystem& system, const ContactSearch& search,
                          std::vector<Contact>& contacts);

}  // namespace ddafit
