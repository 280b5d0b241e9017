#include "forward/substep/prepare_contacts.hpp"
#include "forward/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "forward/contact/contact_law.hpp"
#include "forward/mass_matrix.hpp"

namespace ddafit {

void compute_block_masses(const BlockSystem& s, std::vector<BlockMass>& masses) {
  masses.resize(s.blocks.size());
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    const Block& block = s.blocks[b];
    BlockMass& out = masses[b];
    out = BlockMass{};
    if (block.fixed) continue;
    out.moves = true;
    // The rigid-body rows of the DDA mass matrix (forward/mass_matrix.hpp): rho S on the
    // translations, rho (S_xx + S_yy) on the rotation, no coupling between them.
    const double rho = s.density[block.material];
    out.inverse_mass = 1.0 / (rho * block.area);
    out.inverse_inertia = 1.0 / (rho * (block.s_xx + block.s_yy));
  }
}

void prepare_contacts(SubstepContext& ctx, double h, double deep_overlap) {
  const BlockSystem& s = ctx.system;
  const std::vector<BlockMass>& masses = ctx.state.masses;
  const double slop = ctx.detection.settings.linear_slop;
  std::vector<ContactManifold>& manifolds = ctx.contacts.manifolds;
  const long n = static_cast<long>(manifolds.size());
  ctx.state.pair_blocks.resize(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    ContactManifold& m = manifolds[k];
    ctx.state.pair_blocks[k] = {m.block_a, m.block_b};
    const BlockMass& ma = masses[m.block_a];
    const BlockMass& mb = masses[m.block_b];
    const Interface& face = s.interfaces[m.interface];
    const auto size = [&](int b) { return s.blocks[b].fixed ? 1e300 : std::sqrt(std::abs(s.blocks[b].area)); };
    m.deep_overlap = std::max(slop, deep_overlap * std::min(size(m.block_a), size(m.block_b)));
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      const auto effective = [&](const Vec2& d) {
        return rigid_effective_mass(ma.inverse_mass, ma.inverse_inertia, mb.inverse_mass, mb.inverse_inertia, p.ra,
                                    p.rb, d);
      };
      p.impulse.normal_mass = effective(m.normal);
      p.impulse.tangent_mass = effective(m.tangent);
      p.impulse.step_normal = p.impulse.step_tangent = 0.0;
      p.impulse.tension = h * tensile_capacity(face, p);
      p.impulse.cohesion = h * cohesive_strength(face, p);
    }
  }
}

std::vector<std::vector<int>> colour_manifolds(const BlockSystem& s, const std::vector<ContactManifold>& manifolds,
                                               const Vec2& up) {
  std::vector<std::vector<int>> colours(kSerialColour + 1);
  std::vector<std::uint64_t> used(s.blocks.size(), 0);
  // The manifolds from the lowest up: each one's height is the mean of its points' along `up`.
  const int n = static_cast<int>(manifolds.size());
  std::vector<double> height(manifolds.size(), 0.0);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (int k = 0; k < n; ++k) {
    const ContactManifold& m = manifolds[k];
    double sum = 0.0;
    for (int q = 0; q < m.point_count; ++q) sum += m.points[q].anchor.dot(up);
    height[k] = m.point_count > 0 ? sum / m.point_count : 0.0;
  }
  std::vector<int> order(manifolds.size());
  for (int k = 0; k < n; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return height[a] < height[b]; });
  for (const int k : order) {
    const ContactManifold& m = manifolds[k];
    const bool fa = s.blocks[m.block_a].fixed, fb = s.blocks[m.block_b].fixed;
    // A fixed block never changes velocity, so it does not constrain the colouring.
    const std::uint64_t taken = (fa ? 0 : used[m.block_a]) | (fb ? 0 : used[m.block_b]);
    const int colour = std::min(std::countr_one(taken), kSerialColour);
    if (colour < kSerialColour) {
      if (!fa) used[m.block_a] |= std::uint64_t{1} << colour;
      if (!fb) used[m.block_b] |= std::uint64_t{1} << colour;
    }
    colours[colour].push_back(k);
  }
  while (!colours.empty() && colours.back().empty()) colours.pop_back();
  return colours;
}

}  // namespace ddafit
