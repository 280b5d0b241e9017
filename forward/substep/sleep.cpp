#include "forward/substep/sleep.hpp"

#include <cmath>

#include "forward/block_groups.hpp"

namespace ddafit {
namespace {

// Free blocks joined by a manifold with a point touching (within the slop) or carrying load:
// a resting group. Fixed blocks join nothing (every block on the bedrock would be one group).
BlockGroups touching_groups(const BlockSystem& s, const ContactSet& contacts, bool any_point) {
  BlockGroups g(s.blocks.size());
  for (const ContactManifold& m : contacts.manifolds) {
    if (s.blocks[m.block_a].fixed || s.blocks[m.block_b].fixed) continue;
    bool joined = any_point && m.point_count > 0;
    for (int q = 0; q < m.point_count && !joined; ++q)
      joined = m.points[q].separation <= 0.0 || m.points[q].impulse.normal > 0.0;
    if (joined) g.join(m.block_a, m.block_b);
  }
  return g;
}

}  // namespace

void wake_touched_groups(const BlockSystem& s, const ContactSet& contacts, const std::vector<double>& reach,
                         SleepState& sleep) {
  if (!sleep.enabled()) return;
  bool any_asleep = false;
  for (const char a : sleep.asleep) any_asleep = any_asleep || a;
  if (!any_asleep) return;
  std::vector<char> wake_root(s.blocks.size(), 0);
  BlockGroups g = touching_groups(s, contacts, true);
  bool any = false;
  for (const ContactManifold& m : contacts.manifolds) {
    const int a = m.block_a, b = m.block_b;
    for (const auto& [sleeper, other] : {std::pair{a, b}, std::pair{b, a}}) {
      if (!sleep.asleep[sleeper] || s.blocks[other].fixed || sleep.asleep[other]) continue;
      if (vertex_speed_bound(s.blocks[other], reach[other]) < sleep.sleep_speed) continue;
      wake_root[g.find(sleeper)] = 1;
      any = true;
    }
  }
  if (!any) return;
  std::vector<char> counted(s.blocks.size(), 0);
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const int root = g.find(static_cast<int>(b));
    if (!sleep.asleep[b] || !wake_root[root]) continue;
    sleep.asleep[b] = 0;
    sleep.rest_time[b] = 0.0;
    if (!counted[root]) counted[root] = 1, ++sleep.wakes;
  }
}

void mask_sleeping(const SleepState& sleep, std::vector<BlockMass>& masses) {
  if (!sleep.enabled()) return;
  for (size_t b = 0; b < masses.size(); ++b)
    if (sleep.asleep[b]) masses[b] = BlockMass{};
}

void drop_sleeping_manifolds(const std::vector<ContactManifold>& manifolds, const std::vector<BlockMass>& masses,
                             std::vector<std::vector<int>>& colours) {
  for (std::vector<int>& colour : colours)
    std::erase_if(colour, [&](int k) { return !masses[manifolds[k].block_a].moves && !masses[manifolds[k].block_b].moves; });
}

bool everything_asleep(const BlockSystem& s, const SleepState& sleep) {
  if (!sleep.enabled()) return false;
  for (size_t b = 0; b < s.blocks.size(); ++b)
    if (!s.blocks[b].fixed && !sleep.asleep[b]) return false;
  return true;
}

void update_sleep(BlockSystem& s, const ContactSet& contacts, const std::vector<double>& reach, double dt,
                  SleepState& sleep) {
  if (!sleep.enabled()) return;
  const size_t n = s.blocks.size();
  for (size_t b = 0; b < n; ++b) {
    if (s.blocks[b].fixed) continue;
    if (sleep.asleep[b]) {
      ++sleep.block_steps_asleep;
      continue;
    }
    sleep.rest_time[b] = vertex_speed_bound(s.blocks[b], reach[b]) < sleep.sleep_speed ? sleep.rest_time[b] + dt : 0.0;
  }
  BlockGroups g = touching_groups(s, contacts, false);
  std::vector<char> ready(n, 1);
  for (size_t b = 0; b < n; ++b)
    if (!s.blocks[b].fixed && !sleep.asleep[b] && sleep.rest_time[b] < sleep.sleep_time) ready[g.find(static_cast<int>(b))] = 0;
  for (size_t b = 0; b < n; ++b) {
    if (s.blocks[b].fixed || sleep.asleep[b] || !ready[g.find(static_cast<int>(b))]) continue;
    sleep.asleep[b] = 1;
    s.blocks[b].velocity.setZero();
  }
}

}  // namespace ddafit
