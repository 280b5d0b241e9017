// Split impulses' push-out sweep (solve_contacts.hpp, push_out_overlaps): after the velocity
// sweeps, the overlaps beyond the slop are pushed out by velocities of their own, which move
// the blocks and are then dropped.
#include <algorithm>
#include <cmath>

#include "forward/parallel.hpp"
#include "forward/substep/coloured_sweep.hpp"
#include "forward/substep/solve_contacts.hpp"

namespace ddafit {
namespace {

// The push-out at one point (push_out_overlaps): towards bias_rate x its excess over the slop,
// never pulling. A point without an excess and without a push-out impulse is skipped.
inline PassChange push_out_point(const ContactManifold& m, ContactPoint& p, const SweepSettings& settings,
                                 const SweepState& st, Vec3& ua, Vec3& ub, const BlockMass& ma, const BlockMass& mb) {
  const double excess = std::min(0.0, current_gap(m, p, st.step_moves) + settings.linear_slop);
  const double target = std::min(-settings.softness.bias_rate * excess, settings.max_pushout_speed);
  if (target <= 0.0 && p.impulse.push_out == 0.0) return {};
  const double un = normal_rate(m, p, st.push_velocity);
  const double total = std::max(p.impulse.push_out + p.impulse.normal_mass * (target - un), 0.0);
  const double change = total - p.impulse.push_out;
  apply_impulse(ua, ub, ma, mb, p, change * m.normal);
  p.impulse.push_out = total;
  return {std::abs(change), total};
}

template <int N>
void push_out_batch(std::vector<ContactManifold>& manifolds, const int* ids, const SweepSettings& settings,
                    SweepState& st) {
  ContactManifold* m[N];
  for (int i = 0; i < N; ++i) {
    m[i] = &manifolds[ids[i]];
    for (int q = 0; q < m[i]->point_count; ++q) m[i]->points[q].impulse.push_out = 0.0;
  }
  converge_passes<N>(m, settings.manifold_passes, kManifoldPassTolerance, [&](int i, int q) {
    const ContactManifold& mi = *m[i];
    return push_out_point(mi, m[i]->points[q], settings, st, st.push_velocity[mi.block_a],
                          st.push_velocity[mi.block_b], st.masses[mi.block_a], st.masses[mi.block_b]);
  });
}

}  // namespace

void push_out_overlaps(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                       const SweepSettings& settings, SweepState& st) {
  st.push_velocity.assign(st.velocity.size(), Vec3::Zero());
  // Only a manifold with a point past the slop is pushed (a point without an excess and
  // without a push-out impulse is skipped below): find them in one pass through the
  // manifolds in memory order, so the coloured sweep, which visits them out of order,
  // touches these few only. The moves do not change during the sweep; the answer is the
  // same to the bit (section VII degraded's history identical, docs/performance.md).
  const long n = static_cast<long>(manifolds.size());
  st.overlapping.resize(n);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    const ContactManifold& m = manifolds[k];
    char any = 0;
    for (int q = 0; q < m.point_count; ++q) any |= current_gap(m, m.points[q], st.step_moves) + settings.linear_slop < 0.0;
    st.overlapping[k] = any;
  }
  sweep_coloured(
      colours, [&](int k) { return st.overlapping[k] != 0; },
      [&](const int* ids) { push_out_batch<kSweepBatch>(manifolds, ids, settings, st); },
      [&](int k) { push_out_batch<1>(manifolds, &k, settings, st); });
}

}  // namespace ddafit
