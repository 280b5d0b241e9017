// Groups of blocks joined pairwise (union-find with path halving): the islands that sleeping
// (substep/sleep.cpp) and the implicit solver's impact sweeps (step/resolve_impacts.cpp)
// treat one at a time. Callers join free blocks only: a fixed block would join everything
// resting on it into one group.
#pragma once

#include <numeric>
#include <vector>

namespace ddafit {

struct BlockGroups {
  std::vector<int> parent;
  explicit BlockGroups(size_t blocks) : parent(blocks) { std::iota(parent.begin(), parent.end(), 0); }
  // The group's representative block.
  int find(int b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace ddafit
