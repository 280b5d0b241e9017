// Linearisation of a vertex-edge contact in the step's unknowns (Shi 1993 section 4;
// ../docs/theory.md "Contacts"). Shared by assembly and by the open-close check so the
// two always see the same springs.
#pragma once

#include "forward/block_system.hpp"
#include "forward/contact.hpp"

namespace ddafit {

struct ContactLinearization {
  double edge_length = 0.0;  // l = |P3 - P2|
  Vec2 tangent = Vec2::Zero();  // t = (P3 - P2) / l
  Vec2 reference_point = Vec2::Zero();  // P0 on the edge, fixed to block j
  // Normal: A = l * d_n ~ area0 + e . D_i + g . D_j   (A < 0 = penetration)
  double area0 = 0.0;
  Vec6 e = Vec6::Zero();
  Vec6 g = Vec6::Zero();
  // Shear offset of P1 from P0 along t: d_s ~ shear0 + es . D_i + gs . D_j.
  // es . D_i + gs . D_j alone is the slip of P1 relative to block j over the step.
  double shear0 = 0.0;
  Vec6 es = Vec6::Zero();
  Vec6 gs = Vec6::Zero();
};

inline ContactLinearization linearize_contact(const BlockSystem& s, const Contact& c) {
  ContactLinearization lin;
  const Vec2& p1 = s.vertices[c.vertex];
  const Vec2& p2 = s.vertices[c.edge];
  const Vec2& p3 = s.vertices[s.next_vertex(c.edge)];
  const Vec2 ci = s.blocks[c.block_i].centroid;
  const Vec2 cj = s.blocks[c.block_j].centroid;
  const Vec2 d = p3 - p2;
  lin.edge_length = d.norm();
  lin.tangent = d / lin.edge_length;
  lin.reference_point = p2 + c.reference_ratio * d;

  // A = (x1 - x2)(y3 - y2) - (y1 - y2)(x3 - x2) and its gradients (formulation digest).
  lin.area0 = (p1.x() - p2.x()) * (p3.y() - p2.y()) - (p1.y() - p2.y()) * (p3.x() - p2.x());
  lin.e = displacement_matrix_transpose_times(p1, ci, Vec2(p3.y() - p2.y(), p2.x() - p3.x()));
  lin.g = displacement_matrix_transpose_times(p2, cj, Vec2(p1.y() - p3.y(), p3.x() - p1.x())) +
          displacement_matrix_transpose_times(p3, cj, Vec2(p2.y() - p1.y(), p1.x() - p2.x()));

  lin.shear0 = (p1 - lin.reference_point).dot(lin.tangent);
  lin.es = displacement_matrix_transpose_times(p1, ci, lin.tangent);
  lin.gs = -displacement_matrix_transpose_times(lin.reference_point, cj, lin.tangent);
  return lin;
}

// Value of a linear form over the step's unknowns; a fixed block contributes nothing.
inline double contact_form(const Vec6& a, const Vec6& b, const Block& bi, const Block& bj,
                           const Eigen::VectorXd& d) {
  double r = 0.0;
  if (bi.unknown >= 0) r += a.dot(d.segment<6>(6 * bi.unknown));
  if (bj.unknown >= 0) r += b.dot(d.segment<6>(6 * bj.unknown));
  return r;
}

}  // namespace ddafit
