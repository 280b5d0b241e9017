#include "forward/contact/overlap.hpp"

#include <algorithm>
#include <cmath>

namespace ddafit {

void note_overlap(const BlockSystem& s, const ContactManifold& m, double depth, double time, WorstOverlap& worst) {
  const auto size = [&](int b) { return s.blocks[b].fixed ? 1e300 : std::sqrt(std::abs(s.blocks[b].area)); };
  const double ratio = depth / std::min(size(m.block_a), size(m.block_b));
  if (ratio <= worst.ratio) return;
  worst = {depth, ratio, time, m.block_a, m.block_b};
}

}  // namespace ddafit
