#include "forward/substep/prepare_contacts.hpp"
#include "forward/parallel.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "forward/contact/contact_law.hpp"
#include "forward/mass_matrix.hpp"
#include "forward/substep/solve_contacts.hpp"

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

// The quiet start (ctx.settling) holds a bonded point glued: no tension cut-off and no
// cohesive cap (model revision 2026-12-06.16). Its first substeps start from no impulse and
// overshoot while they take up the weight, and a chain hung by bonds 1.05-1.5 times its
// weight tore its top bond before the clock ran (11-24 of 32 held; tests/test_bonds.cpp):
// the joint opened at its strength by more than the slop, and at t = 0 a joint open wider
// than the slop forms no bond again. Glued, every joint takes its share of the weight
// where it was given; the clock starts with the bonds' own caps (solve_contacts.cpp,
// cap_carried_tension: a joint whose net pull is past them tears then).
constexpr double kGlued = std::numeric_limits<double>::infinity();

void prepare_contacts(SubstepContext& ctx, double h, double deep_overlap, double warm_ratio) {
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
      const bool glued = ctx.settling && p.bonded;
      p.impulse.tension = glued ? kGlued : h * tensile_capacity(face, p);
      p.impulse.cohesion = glued ? kGlued : h * cohesive_strength(face, p);
      if (warm_ratio != 1.0) rescale_warm_start(p.impulse, warm_ratio);
    }
  }
}

void order_by_key(const std::vector<double>& key, std::vector<int>& order) {
  const size_t n = key.size();
  // A double's bits as an unsigned integer in the same order: negative numbers with every
  // bit flipped, the others with the sign bit set. Adding 0.0 turns -0.0 into 0.0.
  struct Item {
    std::uint64_t bits;
    int id;
  };
  std::vector<Item> items(n), spare(n);
  std::uint64_t counts[8][256] = {};
  for (size_t i = 0; i < n; ++i) {
    const std::uint64_t b = std::bit_cast<std::uint64_t>(key[i] + 0.0);
    items[i] = {(b >> 63) ? ~b : b | (std::uint64_t{1} << 63), static_cast<int>(i)};
    for (int d = 0; d < 8; ++d) ++counts[d][(items[i].bits >> (8 * d)) & 0xff];
  }
  // Each pass is stable, so the items end in key order with ties in id order. A byte that
  // every key shares (the exponent's, over one slope) is skipped.
  for (int d = 0; d < 8; ++d) {
    std::uint64_t* count = counts[d];
    if (n == 0 || count[(items[0].bits >> (8 * d)) & 0xff] == n) continue;
    std::uint64_t start = 0;
    for (int v = 0; v < 256; ++v) {
      const std::uint64_t c = count[v];
      count[v] = start;
      start += c;
    }
    for (const Item& item : items) spare[count[(item.bits >> (8 * d)) & 0xff]++] = item;
    items.swap(spare);
  }
  order.resize(n);
  for (size_t i = 0; i < n; ++i) order[i] = items[i].id;
}

std::vector<std::vector<int>> colour_manifolds(const BlockSystem& s, const std::vector<ContactManifold>& manifolds,
                                               const Vec2& up) {
  std::vector<std::vector<int>> colours(kSerialColour + 1);
  std::vector<std::uint64_t> used(s.blocks.size(), 0);
  // The manifolds from the lowest up: each one's height is the mean of its points' along `up`.
  const int n = static_cast<int>(manifolds.size());
  std::vector<double> height(manifolds.size(), 0.0);
  // Per manifold, its two blocks, -1 for a fixed one: a fixed block never changes velocity, so
  // it does not constrain the colouring. Read by the greedy pass below, on one thread, from
  // these 8 bytes rather than from a 576-byte manifold and two blocks.
  std::vector<std::array<int, 2>> free_pair(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (int k = 0; k < n; ++k) {
    const ContactManifold& m = manifolds[k];
    double sum = 0.0;
    for (int q = 0; q < m.point_count; ++q) sum += m.points[q].anchor.dot(up);
    height[k] = m.point_count > 0 ? sum / m.point_count : 0.0;
    free_pair[k] = {s.blocks[m.block_a].fixed ? -1 : m.block_a, s.blocks[m.block_b].fixed ? -1 : m.block_b};
  }
  std::vector<int> order;
  order_by_key(height, order);
  for (const int k : order) {
    const auto [a, b] = free_pair[k];
    const std::uint64_t taken = (a < 0 ? 0 : used[a]) | (b < 0 ? 0 : used[b]);
    const int colour = std::min(std::countr_one(taken), kSerialColour);
    if (colour < kSerialColour) {
      if (a >= 0) used[a] |= std::uint64_t{1} << colour;
      if (b >= 0) used[b] |= std::uint64_t{1} << colour;
    }
    colours[colour].push_back(k);
  }
  while (!colours.empty() && colours.back().empty()) colours.pop_back();
  return colours;
}

}  // namespace ddafit
