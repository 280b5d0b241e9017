// The implicit solver's contact springs are linearisations, in the step's unknowns, of the
// gap and the shear offset at a manifold point (forward/step/point_springs.hpp; formulation
// digest, "Contacts"). Checked, as the digest asks, against finite differences of the exact
// geometry: both blocks moved by a small D with the exact rotation, and the contact measured
// again on the moved polygons.
#include <gtest/gtest.h>

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/manifold.hpp"
#include "forward/step/point_springs.hpp"

namespace ddafit {
namespace {

// A tilted block whose lower-left corner presses 1 mm into the top face of a lower block:
// one vertex-face point with the lower block's face as the reference.
Scene two_blocks(double overlap) {
  Scene s;
  s.duration = 1;
  s.max_step = 1e-3;
  s.materials.push_back({"rock", 2700, 5e9, 0.25});
  BlockInput lower{"lower", "lower", 0, false, {{0, 0}, {3, 0}, {3, 1}, {0, 1}}};
  const Vec2 corner(1.2, 1.0 - overlap);
  const Vec2 along(std::cos(0.3), std::sin(0.3)), up(-along.y(), along.x());
  BlockInput upper{"upper", "upper", 0, false, {corner, corner + along, corner + along + up, corner + up}};
  s.blocks = {lower, upper};
  return s;
}

std::vector<Vec2> moved(const BlockSystem& s, int b, const Vec6& d) {
  const Block& block = s.blocks[b];
  std::vector<Vec2> out;
  for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
    out.push_back(s.vertices[v] + exact_point_displacement(s.vertices[v], block.centroid, d));
  return out;
}

// The gap at the point with id `id` after moving block a by da and block b by db, and the
// position of the incident vertex along the reference face's tangent (the shear measure).
struct Measured {
  double gap = 0.0;
  double along = 0.0;
};

Measured measure(const BlockSystem& s, const Vec6& da, const Vec6& db, std::uint32_t id, const Vec2& tangent) {
  ManifoldSettings settings;
  settings.max_distance = 0.01;
  settings.linear_slop = 1e-6;
  const std::vector<Vec2> a = moved(s, 0, da), b = moved(s, 1, db);
  const Manifold m = collide_polygons(a, b, settings);
  for (int k = 0; k < m.point_count; ++k) {
    if (m.points[k].id != id) continue;
    // The incident vertex (on b) measured from a's reference vertex 3 -> 2 direction.
    const Vec2 vertex = b[static_cast<size_t>(m.points[k].vertex)];
    return {m.points[k].separation, (vertex - a[2]).dot(tangent)};
  }
  ADD_FAILURE() << "the point left the manifold";
  return {};
}

TEST(ContactLinearization, GapAndShearGradientsMatchTheExactGeometry) {
  const BlockSystem s = build_block_system(two_blocks(0.0));
  ManifoldSettings settings;
  settings.max_distance = 0.01;
  settings.linear_slop = 1e-6;
  const std::vector<Vec2> a = moved(s, 0, Vec6::Zero()), b = moved(s, 1, Vec6::Zero());
  const Manifold geometry = collide_polygons(a, b, settings);
  ASSERT_EQ(geometry.point_count, 1);
  ASSERT_EQ(geometry.points[0].owner, 1);  // the upper block's corner on the lower's face

  ContactManifold m;
  m.block_a = 0;
  m.block_b = 1;
  m.normal = geometry.normal;
  m.tangent = Vec2(m.normal.y(), -m.normal.x());
  ContactPoint p;
  p.anchor = geometry.points[0].point;
  p.separation = geometry.points[0].separation;
  const PointSprings lin = point_springs(s, m, p);
  EXPECT_NEAR(lin.gap0, 0.0, 1e-12);

  // Central differences with h = 1e-6 on the exact motion: the error is O(h^2) of terms of
  // order 1 (the gap's second derivative in a rotation is the lever arm, ~1 m), so 1e-8
  // separates a wrong gradient from round-off and curvature.
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vec6 d = Vec6::Zero();
    d[k] = h;
    const Measured a_plus = measure(s, d, Vec6::Zero(), geometry.points[0].id, m.tangent);
    const Measured a_minus = measure(s, -d, Vec6::Zero(), geometry.points[0].id, m.tangent);
    const Measured b_plus = measure(s, Vec6::Zero(), d, geometry.points[0].id, m.tangent);
    const Measured b_minus = measure(s, Vec6::Zero(), -d, geometry.points[0].id, m.tangent);
    EXPECT_NEAR((a_plus.gap - a_minus.gap) / (2 * h), lin.normal_a[k], 1e-8) << "normal_a[" << k << "]";
    EXPECT_NEAR((b_plus.gap - b_minus.gap) / (2 * h), lin.normal_b[k], 1e-8) << "normal_b[" << k << "]";
    // Shear: b's vertex moving along t relative to a material point of a under it. The
    // vertex measured from a's corner 2 moves with a; the point under the vertex does too.
    EXPECT_NEAR((b_plus.along - b_minus.along) / (2 * h), lin.shear_b[k], 1e-8) << "shear_b[" << k << "]";
  }
}

// The springs' gap at D = 0 is the manifold's separation: negative when the corner is
// inside the other block, positive when apart.
TEST(ContactLinearization, PenetrationIsNegative) {
  for (const double overlap : {0.002, -0.002}) {
    const BlockSystem s = build_block_system(two_blocks(overlap));
    ManifoldSettings settings;
    settings.max_distance = 0.01;
    settings.linear_slop = 1e-6;
    const Manifold geometry = collide_polygons(moved(s, 0, Vec6::Zero()), moved(s, 1, Vec6::Zero()), settings);
    ASSERT_GE(geometry.point_count, 1);
    EXPECT_NEAR(geometry.points[0].separation, -overlap, 1e-12);
  }
}

}  // namespace
}  // namespace ddafit
