// The contact springs are linearisations of the normal distance and the shear offset in
// the step's unknowns (formulation digest, "Contacts"). Checked against finite
// differences of the exact geometry, as the digest asks.
#include <gtest/gtest.h>

#include "forward/block_system.hpp"
#include "forward/contact_geometry.hpp"

namespace ddafit {
namespace {

Scene two_blocks() {
  Scene s;
  s.duration = 1;
  s.max_step = 1e-3;
  s.materials.push_back({"rock", 2700, 5e9, 0.25});
  BlockInput lower{"lower", "lower", 0, false, {{0, 0}, {3, 0.2}, {2.9, 1.4}, {0.1, 1.1}}};
  BlockInput upper{"upper", "upper", 0, false, {{1.2, 1.25}, {2.2, 1.3}, {2.1, 2.3}, {1.1, 2.2}}};
  s.blocks = {lower, upper};
  return s;
}

// Normal "area" A of vertex p1 against edge p2->p3, straight from the definition.
double area(const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  return (p1.x() - p2.x()) * (p3.y() - p2.y()) - (p1.y() - p2.y()) * (p3.x() - p2.x());
}

TEST(ContactLinearization, GradientsMatchFiniteDifferences) {
  const BlockSystem s = build_block_system(two_blocks());
  Contact c;
  c.block_i = 1;  // upper block's first vertex ...
  c.vertex = s.blocks[1].first_vertex;
  c.block_j = 0;  // ... against the lower block's top edge (vertices 2 -> 3)
  c.edge = s.blocks[0].first_vertex + 2;
  c.reference_ratio = 0.4;
  const ContactLinearization lin = linearize_contact(s, c);
  const Vec2 p1 = s.vertices[c.vertex], p2 = s.vertices[c.edge], p3 = s.vertices[s.next_vertex(c.edge)];
  EXPECT_NEAR(lin.area0, area(p1, p2, p3), 1e-14);

  // Central differences with h = 1e-6 on the first-order map: the error is O(h^2) of
  // terms of order 1, so 1e-8 separates a wrong gradient from round-off.
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vec6 d = Vec6::Zero();
    d[k] = h;
    const Mat26 ti = displacement_matrix(p1, s.blocks[1].centroid);
    const double da_i = (area(p1 + ti * d, p2, p3) - area(p1 - ti * d, p2, p3)) / (2 * h);
    EXPECT_NEAR(da_i, lin.e[k], 1e-8) << "e[" << k << "]";
    const Vec2 c0 = s.blocks[0].centroid;
    const Mat26 t2 = displacement_matrix(p2, c0), t3 = displacement_matrix(p3, c0);
    const double da_j = (area(p1, p2 + t2 * d, p3 + t3 * d) - area(p1, p2 - t2 * d, p3 - t3 * d)) / (2 * h);
    EXPECT_NEAR(da_j, lin.g[k], 1e-8) << "g[" << k << "]";
    // Shear: offset of p1 from the reference point along t, with t held fixed.
    const Vec2 p0 = p2 + c.reference_ratio * (p3 - p2);
    const Mat26 t0 = displacement_matrix(p0, c0);
    const double ds_i = ((p1 + ti * d - p0).dot(lin.tangent) - (p1 - ti * d - p0).dot(lin.tangent)) / (2 * h);
    const double ds_j = ((p1 - p0 - t0 * d).dot(lin.tangent) - (p1 - p0 + t0 * d).dot(lin.tangent)) / (2 * h);
    EXPECT_NEAR(ds_i, lin.es[k], 1e-8) << "es[" << k << "]";
    EXPECT_NEAR(ds_j, lin.gs[k], 1e-8) << "gs[" << k << "]";
  }
}

TEST(ContactLinearization, PenetrationIsNegative) {
  // Vertex below the top edge of a counter-clockwise block is inside: d_n < 0.
  const BlockSystem s = build_block_system(two_blocks());
  const Vec2 p2 = s.vertices[s.blocks[0].first_vertex + 2], p3 = s.vertices[s.blocks[0].first_vertex + 3];
  const Vec2 inside = 0.5 * (p2 + p3) + Vec2(0, -0.01);
  const Vec2 outside = 0.5 * (p2 + p3) + Vec2(0, 0.01);
  EXPECT_LT(area(inside, p2, p3), 0.0);
  EXPECT_GT(area(outside, p2, p3), 0.0);
}

}  // namespace
}  // namespace ddafit
