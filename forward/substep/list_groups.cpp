#include "forward/substep/list_groups.hpp"

#include "forward/block_groups.hpp"

namespace ddafit {

void group_by_blocks(const std::vector<int>& list, const std::vector<std::array<int, 2>>& pairs,
                     const std::vector<BlockMass>& masses, ListGroups& out) {
  out.ids.clear();
  out.first.assign(1, 0);
  if (list.empty()) return;
  // Join the moving blocks of each manifold; a manifold's group is its moving block's (a
  // manifold with no moving block, which no list holds, would be a group of its own).
  BlockGroups joined(masses.size());
  for (const int k : list) {
    const auto [a, b] = pairs[static_cast<size_t>(k)];
    if (masses[a].moves && masses[b].moves) joined.join(a, b);
  }
  // The groups, numbered by their first manifold in the list.
  std::vector<int> number(masses.size(), -1);  // per root block: its group
  std::vector<int> group(list.size()), size;
  for (size_t i = 0; i < list.size(); ++i) {
    const auto [a, b] = pairs[static_cast<size_t>(list[i])];
    int& slot = number[static_cast<size_t>(joined.find(masses[a].moves ? a : b))];
    if (slot < 0) slot = static_cast<int>(size.size()), size.push_back(0);
    group[i] = slot;
    ++size[static_cast<size_t>(slot)];
  }
  out.first.resize(size.size() + 1);
  for (size_t g = 0; g < size.size(); ++g) out.first[g + 1] = out.first[g] + size[g];
  out.ids.resize(list.size());
  std::vector<int> next(out.first.begin(), out.first.end() - 1);
  for (size_t i = 0; i < list.size(); ++i) {
    int& place = next[static_cast<size_t>(group[i])];
    out.ids[static_cast<size_t>(place++)] = list[i];
  }
}

}  // namespace ddafit
