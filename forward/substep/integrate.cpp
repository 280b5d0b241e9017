#include "forward/substep/integrate.hpp"
#include "forward/substep/parallel.hpp"

#include "forward/step/update_blocks.hpp"

namespace ddafit {

void integrate_velocities(BlockSystem& s, const std::vector<BlockMass>& masses, const Vec2& gravity, double h,
                          std::vector<Vec6>& start_velocity) {
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    Block& block = s.blocks[b];
    start_velocity[b] = block.velocity;
    if (!masses[b].moves) continue;
    // Gravity only: the carried stress is in equilibrium with the contacts
    // (block_stress.hpp), and a uniform body force has no moment about the centroid.
    block.velocity[0] += h * gravity.x();
    block.velocity[1] += h * gravity.y();
  }
}

void integrate_positions(BlockSystem& s, const std::vector<BlockMass>& masses, double h,
                         const std::vector<Vec6>& start_velocity, std::vector<Vec6>& moves,
                         std::vector<Vec6>& step_moves, bool measured) {
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    if (!masses[b].moves) continue;
    const Vec6& v1 = s.blocks[b].velocity;
    const Vec6 d = 0.5 * h * (start_velocity[b] + v1);
    moves[b] = d;
    step_moves[b] += d;
    displace_block(s, static_cast<int>(b), d, measured);
  }
}

}  // namespace ddafit
