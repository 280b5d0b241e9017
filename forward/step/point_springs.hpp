// The springs of a contact point, linear in the step's unknowns (docs/theory.md §3). The
// point p of a manifold (normal n from block a to block b, tangent t) moves with both
// blocks; their relative motion there over the step is T_b(p) D_b - T_a(p) D_a (Shi 1993
// eq. 2.2), and
//   gap   d_n = d_n0 + n . (T_b(p) D_b - T_a(p) D_a)      (< 0: penetration)
//   shear d_s = d_s0 + t . (T_b(p) D_b - T_a(p) D_a)
// with d_n0 the manifold's separation and d_s0 the shear spring's offset at the start of the
// step. n is fixed for the step: the point sits on the reference face's normal through the
// incident feature, so turning n with the reference block changes d_n only at second order.
// Both springs are quadratic potentials in D (the normal one while closed): within a step
// no contact can create energy (Feng's potential-based contact; docs/theory.md §3).
#pragma once

#include <Eigen/Core>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"

namespace ddafit {

struct PointSprings {
  double gap0 = 0.0;             // d_n0, m
  Vec6 normal_a = Vec6::Zero();  // d(d_n)/dD_a = -T_a(p)^T n
  Vec6 normal_b = Vec6::Zero();  // d(d_n)/dD_b =  T_b(p)^T n
  Vec6 shear_a = Vec6::Zero();   // d(d_s)/dD_a = -T_a(p)^T t
  Vec6 shear_b = Vec6::Zero();   // d(d_s)/dD_b =  T_b(p)^T t

  // d_n - d_n0 and d_s - d_s0 for the blocks' step unknowns D_a, D_b (block_step()).
  double normal_move(const Vec6& da, const Vec6& db) const { return normal_a.dot(da) + normal_b.dot(db); }
  double shear_move(const Vec6& da, const Vec6& db) const { return shear_a.dot(da) + shear_b.dot(db); }
};

// A block's six unknowns in the step's solution d; zero for a fixed block, which has none.
inline Vec6 block_step(const Block& b, const Eigen::VectorXd& d) {
  return b.unknown >= 0 ? Vec6(d.segment<6>(6 * b.unknown)) : Vec6::Zero();
}

inline PointSprings point_springs(const BlockSystem& s, const ContactManifold& m, const ContactPoint& p) {
  const Vec2 ca = s.blocks[m.block_a].centroid, cb = s.blocks[m.block_b].centroid;
  PointSprings k;
  k.gap0 = p.separation;
  k.normal_a = displacement_matrix_transpose_times(p.anchor, ca, -m.normal);
  k.normal_b = displacement_matrix_transpose_times(p.anchor, cb, m.normal);
  k.shear_a = displacement_matrix_transpose_times(p.anchor, ca, -m.tangent);
  k.shear_b = displacement_matrix_transpose_times(p.anchor, cb, m.tangent);
  return k;
}

// Slip of b relative to a that counts as sliding in the current iterate. A point that was
// sliding at the start of the step carries its friction force as the pre-load of its shear
// spring, so its slip is the step's relative motion; for one that was locked, the slip is
// the whole offset of the spring (the elastic offset it releases when it lets go is part of
// the same motion).
inline double sliding_slip(const SpringState& c) {
  return c.step_state == ContactState::Sliding ? c.step_slip : c.shear_offset + c.step_slip;
}

}  // namespace ddafit
