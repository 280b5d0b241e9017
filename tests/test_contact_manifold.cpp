// Geometry of the contact stage both solvers share: the contact manifold between two convex pieces
// (the convex decomposition: test_convex_pieces.cpp).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "forward/geometry.hpp"
#include "forward/contact/manifold.hpp"

namespace ddafit {
namespace {

const Vec2 kFar(1000.0, 500.0);  // Vajont-like coordinates: precision must not suffer

std::vector<Vec2> box(double x0, double y0, double x1, double y1) {
  return {kFar + Vec2(x0, y0), kFar + Vec2(x1, y0), kFar + Vec2(x1, y1), kFar + Vec2(x0, y1)};
}

// Square of side 2h centred at c (relative to kFar), rotated by `degrees`.
std::vector<Vec2> square(const Vec2& c, double h, double degrees) {
  const double t = degrees * M_PI / 180.0;
  const Eigen::Matrix2d r{{std::cos(t), -std::sin(t)}, {std::sin(t), std::cos(t)}};
  std::vector<Vec2> p;
  for (const Vec2& v : {Vec2(-h, -h), Vec2(h, -h), Vec2(h, h), Vec2(-h, h)}) p.push_back(kFar + c + r * v);
  return p;
}

// Blocks of ~1 m at ~1 km: positions are good to ~1e-13 m; 1e-9 m leaves room.
constexpr double kLength = 1e-9;
constexpr double kMaxDistance = 0.01, kSlop = 1e-4;

ManifoldSettings settings(double max_distance, double slop, double max_depth = -1.0) {
  ManifoldSettings m;
  m.max_distance = max_distance;
  m.linear_slop = slop;
  m.max_depth = max_depth;
  return m;
}

Manifold collide(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  return collide_polygons(a, b, settings(kMaxDistance, kSlop));
}

// Signed distance of q from the line of the edge of p whose outward normal is n, or NaN.
double distance_from_face(const std::vector<Vec2>& p, const Vec2& n, const Vec2& q) {
  for (size_t k = 0; k < p.size(); ++k) {
    const Vec2 e = p[(k + 1) % p.size()] - p[k];
    if ((Vec2(e.y(), -e.x()).normalized() - n).norm() < 1e-9) return (q - p[k]).dot(n);
  }
  return std::nan("");
}

// What every manifold point must satisfy: the two ends of the point's normal segment lie
// on a's and b's boundaries, the owner's vertex is one of them, and for a face contact
// the separation is the incident end's signed distance from the reference face.
void expect_consistent(const std::vector<Vec2>& a, const std::vector<Vec2>& b, const Manifold& m) {
  ASSERT_GT(m.point_count, 0);
  EXPECT_NEAR(m.normal.norm(), 1.0, 1e-12);
  for (int k = 0; k < m.point_count; ++k) {
    const ManifoldPoint& p = m.points[k];
    const Vec2 on_a = p.point - 0.5 * p.separation * m.normal;
    const Vec2 on_b = p.point + 0.5 * p.separation * m.normal;
    EXPECT_LT(distance_to_boundary(on_a, a), kLength);
    EXPECT_LT(distance_to_boundary(on_b, b), kLength);
    ASSERT_TRUE(p.owner == 0 || p.owner == 1);
    const Vec2 vertex = (p.owner == 0 ? a : b)[static_cast<size_t>(p.vertex)];
    EXPECT_LT((vertex - (p.owner == 0 ? on_a : on_b)).norm(), kLength);
    if (m.point_count == 1 && (p.id & kManifoldIdVertexVertex)) continue;  // no face
    const double from_a = distance_from_face(a, m.normal, on_b);
    const double from_b = distance_from_face(b, -m.normal, on_a);
    ASSERT_TRUE(!std::isnan(from_a) || !std::isnan(from_b));
    EXPECT_NEAR(std::isnan(from_a) ? from_b : from_a, p.separation, kLength);
  }
}

std::vector<double> separations(const Manifold& m) {
  std::vector<double> s;
  for (int k = 0; k < m.point_count; ++k) s.push_back(m.points[k].separation);
  std::sort(s.begin(), s.end());
  return s;
}

std::vector<std::uint32_t> ids(const Manifold& m) {
  std::vector<std::uint32_t> s;
  for (int k = 0; k < m.point_count; ++k) s.push_back(m.points[k].id);
  std::sort(s.begin(), s.end());
  return s;
}

TEST(SubstepManifold, BoxRestingOnBox) {
  const auto a = box(0, 0, 4, 1), b = box(1, 0.99, 3, 1.99);  // 1 cm overlap
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 2);
  EXPECT_LT((m.normal - Vec2(0, 1)).norm(), 1e-12);
  for (const ManifoldPoint& p : m.points) {
    EXPECT_NEAR(p.separation, -0.01, kLength);
    EXPECT_EQ(p.owner, 1);  // b's bottom corners press on a's top
    EXPECT_NEAR(p.point.y() - kFar.y(), 0.995, kLength);
  }
  EXPECT_NE(m.points[0].id, m.points[1].id);
  expect_consistent(a, b, m);
}

TEST(SubstepManifold, BoxesSlightlyApartKeepTwoPoints) {
  // Inside the margin, including equal widths exactly aligned, where the closest points
  // of the two faces are not unique (two points, not the vertex-vertex single point).
  for (double width : {2.0, 4.0}) {
    const auto a = box(0, 0, 4, 1), b = box(4 - width, 1.002, 4, 2.002);
    const Manifold m = collide(a, b);
    ASSERT_EQ(m.point_count, 2);
    EXPECT_LT((m.normal - Vec2(0, 1)).norm(), 1e-12);
    for (const ManifoldPoint& p : m.points) EXPECT_NEAR(p.separation, 0.002, kLength);
    expect_consistent(a, b, m);
  }
}

TEST(SubstepManifold, TiltedBoxAboveFaceIsAFaceContact) {
  // b turned 15 degrees, its lowest corner 2 mm above the middle of a's top: the corner
  // faces a face, not a corner, so the normal stays a's face normal.
  const double t = 15.0 * M_PI / 180.0, reach = 0.5 * (std::cos(t) + std::sin(t));
  const auto a = box(0, 0, 4, 1), b = square(Vec2(2, 1.002 + reach), 0.5, 15.0);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 1);  // b's other bottom corner is 0.26 m up, past the margin
  EXPECT_LT((m.normal - Vec2(0, 1)).norm(), 1e-12);
  EXPECT_NEAR(m.points[0].separation, 0.002, kLength);
  EXPECT_FALSE(m.points[0].id & kManifoldIdVertexVertex);
  EXPECT_EQ(m.points[0].owner, 1);
  expect_consistent(a, b, m);
}

TEST(SubstepManifold, BoxesBeyondMarginHaveNoPoints) {
  EXPECT_EQ(collide(box(0, 0, 4, 1), box(1, 1.02, 3, 2.02)).point_count, 0);
}

TEST(SubstepManifold, CornerToCornerHasOnePointAlongTheCorners) {
  // Two diamonds tip to tip 1 mm apart: the faces' normal would be (1, 1)/sqrt 2, but the
  // contact is between the tips and must push along the line joining them.
  const double gap = 1e-3;
  const auto a = square(Vec2(0, 0), 1.0 / std::sqrt(2.0), 45.0);
  const auto b = square(Vec2(2 + gap, 0), 1.0 / std::sqrt(2.0), 45.0);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 1);
  EXPECT_LT((m.normal - Vec2(1, 0)).norm(), 1e-9);
  EXPECT_NEAR(m.points[0].separation, gap, kLength);
  EXPECT_LT((m.points[0].point - kFar - Vec2(1 + 0.5 * gap, 0)).norm(), kLength);
  expect_consistent(a, b, m);
  // The same pair seen from b: the normal reverses (the other end of each face is nearest).
  const Manifold r = collide(b, a);
  ASSERT_EQ(r.point_count, 1);
  EXPECT_LT((r.normal - Vec2(-1, 0)).norm(), 1e-9);
  EXPECT_LT((r.points[0].point - m.points[0].point).norm(), kLength);
  // Axis-aligned boxes diagonal to each other, both ways round: normal along the diagonal.
  for (int sign : {1, -1}) {
    const double o = sign > 0 ? 0.0 : -2.0 - 2.0 * gap;  // upper at (-1 - gap, -gap)^2
    const auto lower = box(0, 0, 1, 1), upper = box(o + 1 + gap, o + 1 + gap, o + 2 + gap, o + 2 + gap);
    const Manifold d = collide(lower, upper);
    ASSERT_EQ(d.point_count, 1);
    EXPECT_LT((d.normal - sign * Vec2(1, 1).normalized()).norm(), 1e-9);
    EXPECT_NEAR(d.points[0].separation, gap * std::sqrt(2.0), kLength);
    const Vec2 mid = sign > 0 ? Vec2(1 + 0.5 * gap, 1 + 0.5 * gap) : Vec2(-0.5 * gap, -0.5 * gap);
    EXPECT_LT((d.points[0].point - kFar - mid).norm(), kLength);
    expect_consistent(lower, upper, d);
  }
}

TEST(SubstepManifold, CornerToCornerOfNonParallelFaces) {
  // b turned 20 degrees with a corner 2 mm from a corner of a, in the direction 55
  // degrees from a's corner (outside both corners' faces): one point, normal along that
  // line. The scene is turned by k x 90 degrees about a's centre to visit every corner,
  // and mirrored (35 degrees, b turned -20) so that either end of each face is nearest.
  const double gap = 2e-3;
  for (int k = 0; k < 8; ++k) {
    SCOPED_TRACE(k);
    const double mirror = k < 4 ? 1.0 : -1.0;
    const double t = (45.0 + 10.0 * mirror + 90.0 * k) * M_PI / 180.0;
    const double r = (20.0 * mirror + 90.0 * k) * M_PI / 180.0;
    const Vec2 dir(std::cos(t), std::sin(t));
    const Vec2 a_corner = Eigen::Rotation2Dd(0.5 * M_PI * k) * Vec2(1, 1);
    const Vec2 b_corner = a_corner + gap * dir;
    const Vec2 to_centre = 0.5 * Vec2(std::cos(r) - std::sin(r), std::sin(r) + std::cos(r));
    const auto a = square(Vec2(0, 0), 1.0, 0.0), b = square(b_corner + to_centre, 0.5, r * 180.0 / M_PI);
    const Manifold m = collide(a, b);
    ASSERT_EQ(m.point_count, 1);
    EXPECT_LT((m.normal - dir).norm(), 1e-9);
    EXPECT_NEAR(m.points[0].separation, gap, kLength);
    EXPECT_TRUE(m.points[0].id & kManifoldIdVertexVertex);
    EXPECT_LT((m.points[0].point - kFar - 0.5 * (a_corner + b_corner)).norm(), kLength);
    expect_consistent(a, b, m);
  }
}

TEST(SubstepManifold, OverlappingCornersClipAtBothEnds) {
  // b's lower-left corner 1 mm into a's upper-right corner in x and y. The axes tie, a's
  // right face is the reference: one point is b's corner, the other is where b's left
  // face crosses the top end of a's right face -- owned by a's corner there.
  const double d = 1e-3;
  const auto a = box(0, 0, 1, 1), b = box(1 - d, 1 - d, 2 - d, 2 - d);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 2);
  expect_consistent(a, b, m);
  std::vector<std::pair<int, int>> owners;
  for (const ManifoldPoint& p : m.points) {
    EXPECT_NEAR(p.separation, -d, kLength);
    owners.emplace_back(p.owner, p.vertex);
  }
  std::sort(owners.begin(), owners.end());
  EXPECT_EQ(owners, (std::vector<std::pair<int, int>>{{0, 2}, {1, 0}}));
}

TEST(SubstepManifold, TinyTiltedEdgeDoesNotHideContact) {
  // A vertex 1e-10 m inside a's top-right corner (a straight vertex for convex_pieces)
  // makes a tiny edge whose normal points up-left. Taken at face value that axis would
  // "separate" b, resting on a, by 0.35 m; the contact must still be found.
  std::vector<Vec2> a = box(0, 0, 2, 1);
  a.insert(a.begin() + 3, kFar + Vec2(2 - 1e-10, 1 - 1e-10));
  const auto b = box(0.5, 0.99, 1.5, 1.99);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 2);
  EXPECT_LT((m.normal - Vec2(0, 1)).norm(), 1e-9);
  for (const ManifoldPoint& p : m.points) EXPECT_NEAR(p.separation, -0.01, 1e-9);
}

TEST(SubstepManifold, RotatedBoxAtCorner) {
  // b (side 1) sinks 1 cm into a's top-right corner region, at three angles; with a and
  // b swapped the normal must reverse and the separations stay.
  const auto a = box(0, 0, 2, 1);
  for (double degrees : {15.0, 45.0, 90.0}) {
    SCOPED_TRACE(degrees);
    const double t = degrees * M_PI / 180.0, reach = 0.5 * (std::abs(std::cos(t)) + std::abs(std::sin(t)));
    const auto b = square(Vec2(1.9, 1.0 + reach - 0.01), 0.5, degrees);
    const Manifold m = collide(a, b);
    expect_consistent(a, b, m);
    EXPECT_LE(m.points[0].separation, 0.0);
    const Manifold s = collide(b, a);
    expect_consistent(b, a, s);
    EXPECT_LT((s.normal + m.normal).norm(), 1e-12);
    const auto sm = separations(m), ss = separations(s);
    ASSERT_EQ(sm.size(), ss.size());
    for (size_t k = 0; k < sm.size(); ++k) EXPECT_NEAR(sm[k], ss[k], kLength);
  }
}

TEST(SubstepManifold, CornerOfAIntoFaceOfB) {
  // a's top-right corner 1 cm inside the lower-left face of b (turned 40 degrees, beside
  // a): b's face is the reference, so the normal is minus its outward normal, and the
  // one point is a's corner (owner 0, vertex 2).
  const auto a = box(0, 0, 2, 1);
  const double t = 40.0 * M_PI / 180.0;
  const auto b = square(Vec2(2, 1) + 0.49 * Vec2(std::cos(t), std::sin(t)), 0.5, 40.0);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 1);
  EXPECT_LT((m.normal - Vec2(std::cos(t), std::sin(t))).norm(), 1e-12);
  EXPECT_NEAR(m.points[0].separation, -0.01, kLength);
  EXPECT_EQ(m.points[0].owner, 0);
  EXPECT_EQ(m.points[0].vertex, 2);
  expect_consistent(a, b, m);
}

TEST(SubstepManifold, IdsStayWhileTheSameFeaturesTouch) {
  // Move and turn b a little (0.1 mm, 1e-4 rad): same features, so same ids.
  const auto a = box(0, 0, 2, 1);
  for (double degrees : {15.0, 90.0}) {
    SCOPED_TRACE(degrees);
    const double t = degrees * M_PI / 180.0, reach = 0.5 * (std::abs(std::cos(t)) + std::abs(std::sin(t)));
    const Vec2 c(1.9, 1.0 + reach - 0.005);
    const Manifold m0 = collide(a, square(c, 0.5, degrees));
    const Manifold m1 = collide(a, square(c + Vec2(1e-4, -2e-4), 0.5, degrees + 0.0057));
    ASSERT_GT(m0.point_count, 0);
    EXPECT_EQ(ids(m0), ids(m1));
  }
  const double t = 40.0 * M_PI / 180.0;
  const Vec2 c(Vec2(2, 1) + 0.49 * Vec2(std::cos(t), std::sin(t)));
  EXPECT_EQ(ids(collide(a, square(c, 0.5, 40.0))),
            ids(collide(a, square(c + Vec2(-1e-4, 1e-4), 0.5, 40.0057))));
  const Manifold f0 = collide(a, box(0.5, 0.99, 1.5, 1.99));
  const Manifold f1 = collide(a, box(0.5001, 0.9901, 1.5001, 1.9901));
  EXPECT_EQ(ids(f0), ids(f1));
}

TEST(SubstepManifold, StraightVertexDoesNotHalveTheFace) {
  // a's top side has a vertex in its middle; a box spanning it must be held at both ends.
  const std::vector<Vec2> a{kFar, kFar + Vec2(4, 0), kFar + Vec2(4, 1), kFar + Vec2(2, 1), kFar + Vec2(0, 1)};
  const auto b = box(0.5, 0.99, 3.5, 1.99);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 2);
  std::vector<double> x{m.points[0].point.x() - kFar.x(), m.points[1].point.x() - kFar.x()};
  std::sort(x.begin(), x.end());
  EXPECT_NEAR(x[0], 0.5, kLength);
  EXPECT_NEAR(x[1], 3.5, kLength);
}

TEST(SubstepManifold, NearlyParallelFacesApartKeepTwoPoints) {
  // b turned by 1e-7 rad above a, 2 mm apart: still a face contact, not a corner one.
  const auto a = box(0, 0, 2, 1);
  const auto b = square(Vec2(1.0, 1.502), 0.5, 1e-7 * 180.0 / M_PI);
  const Manifold m = collide(a, b);
  ASSERT_EQ(m.point_count, 2);
  for (const ManifoldPoint& p : m.points) EXPECT_NEAR(p.separation, 0.002, 1e-6);
  expect_consistent(a, b, m);
}

// Convex hull (counter-clockwise, no collinear points) by the monotone chain.
std::vector<Vec2> hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& u, const Vec2& v) {
    return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y());
  });
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double gap_between(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double d = std::numeric_limits<double>::infinity();
  for (const Vec2& p : a) d = std::min(d, distance_to_boundary(p, b));
  for (const Vec2& p : b) d = std::min(d, distance_to_boundary(p, a));
  return d;
}

// A piece of a concave block whose top edge is a cut (the block's other piece lies above
// it), and a diamond 0.1 m above that cut. No solid edge of the piece and no edge of the
// diamond separates them (the diamond overhangs both sides of the piece): only the cut
// does. The diamond lies over the block's other piece, whose own manifold holds it; read
// through this piece's solid faces it came out 0.28 m "deep" (on Vajont section VI such a
// reading, 0.62 m, stopped the run). With the top edge solid the same pair is a
// speculative contact 0.1 m apart.
TEST(SubstepManifold, APolygonBeyondACutHasNoContactWithThePiece) {
  const auto piece = box(0, 0, 1, 1);
  const auto diamond = square(Vec2(0.5, 2.1), std::sqrt(0.5), 45.0);  // corners 1 m from (0.5, 2.1)
  const std::vector<char> top_cut = {1, 1, 0, 1}, all_solid = {1, 1, 1, 1};
  const double margin = 0.5;
  const Manifold across = collide_polygons(piece, diamond, settings(margin, kSlop), top_cut);
  EXPECT_EQ(across.point_count, 0);
  const Manifold face = collide_polygons(piece, diamond, settings(margin, kSlop), all_solid);
  ASSERT_GE(face.point_count, 1);
  EXPECT_NEAR(face.points[0].separation, 0.1, kLength);
}

TEST(SubstepManifold, BlockCornerSetInAValleyCornerKeepsItsContact) {
  // Vajont section VII at 12.7 s, as dumped from the run: a toe block slid along the valley
  // floor until its lower right corner sat just past the corner where the opposite bank's
  // 45-degree face starts; its own right face leans at 52 degrees. The block's face is the
  // best axis, but the bank piece's side turned to it is a cut (the bank is concave there),
  // so its best solid face faces away. The pair had no point and the block went into the
  // bank. The contact is the block's corner on the bank's face: 26.6 mm deep in this
  // geometry (distance from the line through the dumped corners); 1 mm covers the dump's
  // rounding.
  const Vec2 o(1537.9, 608.7);
  const std::vector<Vec2> block = {o + Vec2(-2.9105818909, 2.2461282800), o + Vec2(-3.8269892839, 2.9518834235),
                                   o + Vec2(-3.8208732549, 2.0790345175), o + Vec2(-3.8064884919, 0.0261134551),
                                   o + Vec2(0.0238852035, -0.0138002860)};
  const std::vector<Vec2> bank = {o + Vec2(92.0, 92.0), o, o + Vec2(656.0, -208.7), o + Vec2(192.0, 131.5),
                                  o + Vec2(100.0, 98.0)};
  const std::vector<char> block_solid(block.size(), 1), bank_solid = {1, 0, 0, 1, 1};  // the bank piece's cuts
  const double margin = 0.625;
  const Manifold m = collide_polygons(block, bank, settings(margin, 2.5e-4, margin), block_solid, bank_solid);
  ASSERT_GE(m.point_count, 1);
  const ManifoldPoint& deepest =
      m.point_count == 2 && m.points[1].separation < m.points[0].separation ? m.points[1] : m.points[0];
  EXPECT_NEAR(deepest.separation, -(0.0238852035 + 0.0138002860) / std::sqrt(2.0), 1e-3);
  EXPECT_LT((deepest.point - o).norm(), 0.05);                              // at the valley corner
  EXPECT_LT((m.normal - Vec2(1.0, -1.0) / std::sqrt(2.0)).norm(), 1e-6);  // into the bank's 45-degree face
}

// Cut ends (manifold.hpp; model revision 2026-12-06.24). A fixed block spanning a convex kink of
// the ground has a reflex corner in its base, and its decomposition cut that corner off with a
// sliver piece whose top is a single corner V: the block's convex corner at the joint before the
// kink, between the joint's face and the block's top face, which is the other piece's. A 10 m
// slider that had just crossed the joint touched V with its base, 3 um deep; the sliver's side
// turned to that base is the cut, so the contact flipped to the sliver's joint face, 4 cm deep
// along the slope, and threw the slider back and stopped it there (tests/test_ground_joints.cpp).
// V is a convex corner where a cut ends: the other piece, whose top face runs on from V, holds the
// slider, and the sliver gives no contact. At a reflex corner (the toe block in the valley corner
// above) the flip stands.
TEST(SubstepManifold, ACutEndingAtAConvexCornerLeavesTheContactToThePieceBeyondIt) {
  const Vec2 down(std::cos(20.0 * M_PI / 180.0), -std::sin(20.0 * M_PI / 180.0)), up(-down.y(), down.x());
  const Vec2 v(-0.9397, 0.3420);  // V, on the ground's 20 deg surface
  // The joint leans 1 mrad, its foot downslope: its face then turns away from the slider's base,
  // as round-off turned it in the run (a joint square to the surface is the sliver's incident face).
  const std::vector<Vec2> sliver = {v, v - 10.0 * up + 0.01 * down, v - 10.0 * up + 0.563 * down};
  const std::vector<char> solid = {1, 1, 0}, reflex = {0, 0, 1};  // the cut runs from the reflex base corner to V
  // The slider's base on the surface line, 3 um into it, its front corner 4 cm past V.
  const Vec2 front = v + 0.04 * down - 3e-6 * up;
  const std::vector<Vec2> slider = {front - 10.0 * down, front, front + 6.0 * up, front - 10.0 * down + 6.0 * up};
  const Manifold m = collide_polygons(sliver, slider, settings(0.1, 1e-3, 0.1), solid, {}, reflex, {});
  EXPECT_EQ(m.point_count, 0) << "normal " << m.normal.transpose();
  // Without the corners' reflex flags (unknown) the flip stands, as before the rule.
  const Manifold flipped = collide_polygons(sliver, slider, settings(0.1, 1e-3, 0.1), solid, {});
  ASSERT_GE(flipped.point_count, 1);
  EXPECT_LT(flipped.normal.dot(down), -0.99);  // along the joint's face, back up the slope
}

TEST(SubstepManifold, RandomPairsMissNoContact) {
  // Hulls of 3-8 random points, ~1 m across at ~1.5 km, in random relative positions:
  // overlapping or closer than the margin must give points, farther must give none,
  // and every point must sit between the two boundaries.
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec2 far(1500.0, 800.0);
  const double margin = 0.05;
  int touching = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    std::vector<Vec2> pa, pb;
    const Vec2 offset(2.0 * u(rng), 2.0 * u(rng));
    for (int k = 0, n = 3 + trial % 6; k < n; ++k) pa.push_back(far + Vec2(u(rng), u(rng)));
    for (int k = 0, n = 3 + trial % 5; k < n; ++k) pb.push_back(far + offset + Vec2(u(rng), u(rng)));
    const auto a = hull(pa), b = hull(pb);
    if (a.size() < 3 || b.size() < 3) continue;
    const bool overlap = polygons_overlap(a, b, 1e-6);
    const double gap = overlap ? 0.0 : gap_between(a, b);
    const Manifold m = collide_polygons(a, b, settings(margin, kSlop));
    SCOPED_TRACE(trial);
    // 0.1 % either side of the margin: the two sides of the comparison see round-off.
    if (overlap || gap < 0.999 * margin) {
      ASSERT_GT(m.point_count, 0);
      ++touching;
    }
    if (!overlap && gap > 1.001 * margin) {
      EXPECT_EQ(m.point_count, 0);
    }
    for (int k = 0; k < m.point_count; ++k) {
      const ManifoldPoint& p = m.points[k];
      EXPECT_LT(distance_to_boundary(p.point - 0.5 * p.separation * m.normal, a), kLength);
      EXPECT_LT(distance_to_boundary(p.point + 0.5 * p.separation * m.normal, b), kLength);
    }
  }
  EXPECT_GT(touching, 1000);  // the test did look at contacts
}

}  // namespace
}  // namespace ddafit
