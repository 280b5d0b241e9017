#include "forward/substep/refresh_corner_gaps.hpp"

#include <algorithm>

#include "forward/contact/corner_paths.hpp"

namespace ddafit {

void remember_corner_points(const std::vector<ContactManifold>& manifolds, SweepState& state) {
  state.corner_points.clear();
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k)
    if (apart_corners(manifolds[k], manifolds[k].points[0]))
      state.corner_points.push_back({k, manifolds[k].points[0].separation});
}

void refresh_corner_gaps(const BlockSystem& s, const ContactShapes& shapes, double h, double slop,
                         std::vector<ContactManifold>& manifolds, SweepState& state) {
  for (const auto& [k, detected] : state.corner_points) {
    ContactManifold& m = manifolds[k];
    ContactPoint& p = m.points[0];
    p.separation = detected;
    const Vec3 &va = state.velocity[m.block_a], &vb = state.velocity[m.block_b];
    // What the pair can close along the corners' line in the substep, and the slop: a point
    // whose gap is wider pushes nothing in it either way, and needs no paths followed.
    const double reach = h * (velocity_at(vb, p.rb) - velocity_at(va, p.ra)).norm() + slop;
    const double gap = current_gap(m, p, state.step_moves);
    if (gap >= reach) continue;
    if (corners_pass(s, shapes, m, p, detected, state.step_moves[m.block_a], state.step_moves[m.block_b], va, vb, h,
                     slop))
      p.separation += reach - gap;
  }
}

}  // namespace ddafit
