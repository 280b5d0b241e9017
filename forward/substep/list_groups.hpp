// The extra sweeps that run over a list of manifolds in its own order (converge_deep's deep
// neighbourhoods, converge_heavy's light blocks), split into groups that share no moving
// block; coloured_sweep.hpp (sweep_groups) shares the groups between the threads.
//
// Why not colours: in list order Gauss-Seidel carries a load down a column of blocks in one
// sweep; in the step's colours it does not, and nine column and stack tests failed when these
// sweeps ran coloured (docs/performance.md, "Section VII at 20 ms × 4"). Why groups: the
// lists hold the neighbourhoods of a few deep or light blocks scattered through a slide, and
// two manifolds that share no moving block, directly or through a chain of the list's
// manifolds, never read what the other writes (a fixed block's velocity never changes). So
// each group swept alone in list order, its sweeps one after another, gives the numbers of the
// whole list swept in order to the bit, on any number of threads. On one thread these sweeps
// were about a tenth of section VII's main thread while the other waited (docs/performance.md,
// "Section VII: the main thread's one-thread passes shared").
#pragma once

#include <array>
#include <vector>

#include "forward/substep/substep_types.hpp"

namespace ddafit {

// A list's manifolds, group by group: group g is ids[first[g] .. first[g + 1]), in list order.
// Groups are numbered in the order of their first manifold in the list.
struct ListGroups {
  std::vector<int> ids;
  std::vector<int> first;
};

// Splits `list` (manifold ids into `pairs`, their two blocks) into groups joined by a shared
// moving block (block_groups.hpp).
void group_by_blocks(const std::vector<int>& list, const std::vector<std::array<int, 2>>& pairs,
                     const std::vector<BlockMass>& masses, ListGroups& out);

}  // namespace ddafit
