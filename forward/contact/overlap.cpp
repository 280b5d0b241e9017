#include "forward/contact/overlap.hpp"

#include <algorithm>
#include <cmath>

namespace ddafit {

void WorstOverlap::note(const BlockSystem& s, const ContactManifold& m, double depth_now, double time_now) {
  const auto size = [&](int b) { return s.blocks[b].fixed ? 1e300 : std::sqrt(std::abs(s.blocks[b].area)); };
  const double ratio_now = depth_now / std::min(size(m.block_a), size(m.block_b));
  if (ratio_now <= ratio) return;
  *this = {depth_now, ratio_now, time_now, m.block_a, m.block_b};
}

}  // namespace ddafit
