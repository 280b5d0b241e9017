#include "forward/step/sliding_groups.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ddafit {
namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

double largest_normal_force(const ContactSet& contacts) {
  double largest = 0.0;
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q) largest = std::max(largest, m.points[q].spring.normal_force);
  return largest;
}

SlidingGroups sliding_groups(const BlockSystem& s, const ContactSet& contacts, const std::vector<char>& settled,
                             const std::vector<char>& held) {
  const int n = static_cast<int>(s.blocks.size());
  const auto member = [&](int b) { return s.blocks[b].unknown >= 0 && settled[b]; };
  const double largest = largest_normal_force(contacts);
  const auto loaded = [&](const ContactPoint& p) {
    return p.spring.state != ContactState::Open && p.spring.normal_force > kLoadedShare * largest;
  };
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q)
      if (loaded(m.points[q]) && m.points[q].spring.state != ContactState::Sliding && member(m.block_a) &&
          member(m.block_b))
        parent[find(parent, m.block_a)] = find(parent, m.block_b);
  SlidingGroups g;
  g.group.assign(n, -1);
  std::vector<int> id(n, -1);
  for (int b = 0; b < n; ++b) {
    if (!member(b)) continue;
    const int root = find(parent, b);
    if (id[root] < 0) id[root] = static_cast<int>(g.tangent.size()), g.tangent.emplace_back(Vec2::Zero());
    g.group[b] = id[root];
  }
  const size_t groups = g.tangent.size();
  // Each sliding point tells the direction its group slips in against the block across it: s along
  // the tangent for block b against a (SpringState::slip_direction). Slips against the ground (a
  // block that is not a settled free one) are what the group does; slips against another group
  // only say how the two part (the lower block of a weaker joint slips down its face and up
  // against the block above), and are taken where the group slips against no ground. A group
  // whose points slip both ways along one face (a block at rest whose base corners spread apart
  // under its own weight, Poisson's ratio) is not sliding.
  std::vector<Vec2> against[2] = {std::vector<Vec2>(groups, Vec2::Zero()), std::vector<Vec2>(groups, Vec2::Zero())};
  std::vector<char> both_ways[2] = {std::vector<char>(groups, 0), std::vector<char>(groups, 0)};
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q) {
      const SpringState& c = m.points[q].spring;
      if (!loaded(m.points[q]) || c.state != ContactState::Sliding || c.slip_direction == 0.0) continue;
      for (const int b : {m.block_a, m.block_b}) {
        const int k = g.group[b];
        const int other = b == m.block_a ? m.block_b : m.block_a;
        if (k < 0 || g.group[other] == k) continue;
        const int ground = g.group[other] < 0 ? 1 : 0;
        const Vec2 slips = side(m, b) * c.slip_direction * m.tangent;
        Vec2& t = against[ground][k];
        if (t.isZero()) {
          t = slips;
        } else if (!parallel(t, slips)) {
          g.resolved = false;
        } else if (t.dot(slips) < 0.0) {
          both_ways[ground][k] = 1;
        }
      }
    }
  g.on_ground.assign(groups, 0);
  for (size_t k = 0; k < groups; ++k) {
    const int ground = against[1][k].isZero() ? 0 : 1;
    g.on_ground[k] = static_cast<char>(ground);
    if (!both_ways[ground][k]) g.tangent[k] = against[ground][k];
  }
  if (!held.empty())
    for (int b = 0; b < n; ++b)
      if (held[b] && g.group[b] >= 0) g.tangent[g.group[b]].setZero();
  for (size_t k = 0; k < groups; ++k) g.any = g.any || !g.tangent[k].isZero();
  return g;
}

std::vector<double> net_force_along(const BlockSystem& s, const SlidingGroups& g, const Eigen::VectorXd& f) {
  std::vector<double> along(g.tangent.size(), 0.0);
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const int k = g.group[b];
    if (k >= 0 && !g.tangent[k].isZero()) along[k] += g.tangent[k].dot(f.segment<2>(6 * s.blocks[b].unknown));
  }
  return along;
}

}  // namespace ddafit
