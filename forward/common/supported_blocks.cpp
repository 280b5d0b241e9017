#include "forward/common/supported_blocks.hpp"

#include "forward/block_groups.hpp"

namespace ddafit {

std::vector<char> supported_blocks(const BlockSystem& s, const std::vector<ContactManifold>& manifolds, double slop) {
  const size_t n = s.blocks.size();
  const auto touches = [slop](const ContactManifold& m) {
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].separation <= slop) return true;
    return false;
  };
  BlockGroups groups(n);
  for (const ContactManifold& m : manifolds)
    if (!s.blocks[m.block_a].fixed && !s.blocks[m.block_b].fixed && touches(m)) groups.join(m.block_a, m.block_b);
  std::vector<char> grounded(n, 0);  // per group representative
  for (const ContactManifold& m : manifolds) {
    const bool fa = s.blocks[m.block_a].fixed, fb = s.blocks[m.block_b].fixed;
    if (fa != fb && touches(m)) grounded[groups.find(fa ? m.block_b : m.block_a)] = 1;
  }
  std::vector<char> supported(n, 0);
  for (size_t b = 0; b < n; ++b)
    if (!s.blocks[b].fixed) supported[b] = grounded[groups.find(static_cast<int>(b))];
  return supported;
}

}  // namespace ddafit
