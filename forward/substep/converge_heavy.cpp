#include "forward/substep/converge_heavy.hpp"

#include "forward/substep/coloured_sweep.hpp"

namespace ddafit {

const ListGroups& heavy_neighbourhood(const std::vector<ContactManifold>& manifolds, const HeavyNeighbours& settings,
                                      SweepState& st) {
  if (st.heavy) return *st.heavy;
  ListGroups& groups = st.heavy.emplace();
  groups.first.assign(1, 0);
  if (settings.sweeps <= 0 || settings.mass_ratio <= 0.0) return groups;
  const std::vector<std::array<int, 2>>& pairs = pair_blocks(manifolds, st);
  // A block is light when a free neighbour's mass is at least mass_ratio times its own, that
  // is when its inverse mass is at least mass_ratio times the neighbour's.
  std::vector<char> light(st.masses.size(), 0);
  bool any = false;
  for (const auto& [a, b] : pairs) {
    const BlockMass& ma = st.masses[a];
    const BlockMass& mb = st.masses[b];
    if (!ma.moves || !mb.moves) continue;
    if (much_lighter(ma, mb, settings.mass_ratio)) light[a] = 1, any = true;
    if (much_lighter(mb, ma, settings.mass_ratio)) light[b] = 1, any = true;
  }
  if (any) group_by_blocks(manifolds_of_blocks(pairs, light, st.masses), pairs, st.masses, groups);
  return groups;
}

void converge_heavy(std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                    const HeavyNeighbours& settings, SweepState& st) {
  const ListGroups& groups = heavy_neighbourhood(manifolds, settings, st);
  if (groups.ids.empty() || settings.sweeps <= 0) return;
  const double inv_h = 1.0 / relax.h;
  sweep_groups(groups, settings.sweeps,
               [&](int k, char&) { solve_manifold(manifolds[k], st.deep[k], relax, inv_h, st); });
}

}  // namespace ddafit
