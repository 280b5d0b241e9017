#include "forward/substep/list_groups.hpp"

namespace ddafit {
namespace {

// The group a taken block belongs to (union-find with path halving over `root`; a root is its
// own parent).
int find_root(std::vector<int>& root, int b) {
  while (root[b] != b) b = root[b] = root[root[b]];
  return b;
}

}  // namespace

void group_by_blocks(const std::vector<int>& list, const std::vector<std::array<int, 2>>& pairs,
                     const std::vector<BlockMass>& masses, std::vector<int>& root, ListGroups& out) {
  out.ids.clear();
  out.first.assign(1, 0);
  if (list.empty()) return;
  root.resize(masses.size(), -1);
  std::vector<int> touched;
  const auto take = [&](int b) {
    if (root[b] < 0) root[b] = b, touched.push_back(b);
  };
  // Join the moving blocks of each manifold; a manifold's group is its moving block's.
  std::vector<int> block_of(list.size());
  for (size_t i = 0; i < list.size(); ++i) {
    const auto [a, b] = pairs[static_cast<size_t>(list[i])];
    const bool a_moves = masses[a].moves, b_moves = masses[b].moves;
    if (a_moves) take(a);
    if (b_moves) take(b);
    if (a_moves && b_moves) {
      const int ra = find_root(root, a), rb = find_root(root, b);
      if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
    }
    block_of[i] = a_moves ? a : b;
    take(block_of[i]);  // a manifold with no moving block (none is listed) is a group of its own
  }
  // The groups, numbered by their first manifold in the list. Each manifold's root first; then
  // root[] is cleared and reused, a root's slot holding its group's number.
  std::vector<int> roots(list.size());
  for (size_t i = 0; i < list.size(); ++i) roots[i] = find_root(root, block_of[i]);
  for (const int b : touched) root[b] = -1;
  std::vector<int> group(list.size()), size;
  for (size_t i = 0; i < list.size(); ++i) {
    int& slot = root[roots[i]];
    if (slot < 0) slot = static_cast<int>(size.size()), size.push_back(0);
    group[i] = slot;
    ++size[static_cast<size_t>(slot)];
  }
  for (const int r : roots) root[r] = -1;
  out.first.resize(size.size() + 1);
  for (size_t g = 0; g < size.size(); ++g) out.first[g + 1] = out.first[g] + size[g];
  out.ids.resize(list.size());
  std::vector<int> next(out.first.begin(), out.first.end() - 1);
  for (size_t i = 0; i < list.size(); ++i) {
    int& slot = next[static_cast<size_t>(group[i])];
    out.ids[static_cast<size_t>(slot++)] = list[i];
  }
}

}  // namespace ddafit
