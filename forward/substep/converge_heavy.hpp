// Stage 4a of a substep (split impulses), straight after the two velocity sweeps: more sweeps
// where a light block carries or meets a much heavier one. Gauss-Seidel converges slowest at
// a large mass ratio: solving the joint between a slider and a cube under it stops the light
// cube, not the slider, and the cube's own support then hands the slider only the cube's share
// of momentum per sweep (a sweep removes about m_light / m_heavy of the error). Two sweeps are
// enough for the warm-started joints of blocks of similar size, and the thousands of those in
// a landslide get no more; the few manifolds of a light block beside a heavy one get
// kHeavySweeps more, in order, on one thread (as converge_deep's).
//
// Measured on the cube-row class (tests/test_free_row.cpp: a 3 x 1.5 m slider, 450 times a
// 0.1 m cube, arriving at 1-6 m/s on a row of such cubes at 2 ms x 4): with the two sweeps
// alone 12 of 18 runs left seed Eq. 4 by more than 1 % or drove the row; six sweeps for every
// manifold mended all 18; at a ratio of 30, 8 sweeps (advance_step.cpp, kHeavySweeps) mend them
// too (docs/theory.md §13, model revision 2026-12-05.2).
#pragma once

#include <vector>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

struct HeavyNeighbours {
  // A free block at least this many times heavier than a free neighbour makes that neighbour
  // "light": its manifolds get the extra sweeps.
  double mass_ratio = 0.0;
  int sweeps = 0;  // extra relax sweeps over those manifolds, per substep
};

// Whether block `light` is much lighter than its free neighbour `heavy`: the neighbour's mass
// is at least `ratio` times its own, that is its inverse mass at least `ratio` times the
// neighbour's. Also read by the impact groups (solve_impact_group.cpp, has_heavy_pair).
inline bool much_lighter(const BlockMass& light, const BlockMass& heavy, double ratio) {
  return light.inverse_mass >= ratio * heavy.inverse_mass;
}

// The manifolds of the light blocks (HeavyNeighbours::mass_ratio), in order, in groups that share
// no moving block (list_groups.hpp); built once per step (the manifolds and masses do not change
// within it) into state.heavy.
const ListGroups& heavy_neighbourhood(const std::vector<ContactManifold>& manifolds, const HeavyNeighbours& settings,
                                      SweepState& state);

// settings.sweeps relax sweeps over heavy_neighbourhood's manifolds.
void converge_heavy(std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                    const HeavyNeighbours& settings, SweepState& state);

}  // namespace ddafit
