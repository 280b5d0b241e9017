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
};

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

// Value of a linear form over the step's unknowns; a fixed block contributes nothing.
inline double contact_form(const Vec6& a, const Vec6& b, const Block& ba, const Block& bb, const Eigen::VectorXd& d) {
  double r = 0.0;
  if (ba.unknown >= 0) r += a.dot(d.segment<6>(6 * ba.unknown));
  if (bb.unknown >= 0) r += b.dot(d.segment<6>(6 * bb.unknown));
  return r;
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
