// Polygon moments against closed forms, and the exact rotation update.
#include <gtest/gtest.h>

#include <cmath>

#include "forward/geometry.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {
namespace {

// Round-off of sums over a handful of vertices of size ~1e3: 1e-9 relative is ample.
constexpr double kTolerance = 1e-9;

TEST(Geometry, RectangleMomentsMatchClosedForm) {
  // A 4 x 2 rectangle far from the origin, rotated by 30 degrees: the second moments
  // about the centroid are those of the rectangle rotated, independent of position.
  const double a = 4.0, b = 2.0, t = M_PI / 6.0;
  const Vec2 u(std::cos(t), std::sin(t)), v(-std::sin(t), std::cos(t));
  const Vec2 o(1000.0, -500.0);
  const std::vector<Vec2> poly{o, o + a * u, o + a * u + b * v, o + b * v};
  const PolygonMoments m = polygon_moments(poly);
  const double i_u = b * a * a * a / 12.0, i_v = a * b * b * b / 12.0;  // along u, along v
  const double c = std::cos(t), s = std::sin(t);
  EXPECT_NEAR(m.area, a * b, kTolerance * a * b);
  EXPECT_NEAR(m.centroid.x(), (o + 0.5 * a * u + 0.5 * b * v).x(), kTolerance * 1000);
  EXPECT_NEAR(m.centroid.y(), (o + 0.5 * a * u + 0.5 * b * v).y(), kTolerance * 1000);
  EXPECT_NEAR(m.s_xx, c * c * i_u + s * s * i_v, kTolerance * i_u);
  EXPECT_NEAR(m.s_yy, s * s * i_u + c * c * i_v, kTolerance * i_u);
  EXPECT_NEAR(m.s_xy, c * s * (i_u - i_v), kTolerance * i_u);
}

TEST(Geometry, ClockwiseOrderGivesNegativeArea) {
  const std::vector<Vec2> cw{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_DOUBLE_EQ(signed_area(cw), -1.0);  // exact in binary arithmetic
}

TEST(Geometry, ConcavePolygonAreaAndSelfIntersection) {
  // An L shape (area 3) is simple; a bow-tie is not.
  const std::vector<Vec2> l{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_DOUBLE_EQ(polygon_moments(l).area, 3.0);
  EXPECT_EQ(first_self_intersection(l).first, -1);
  const std::vector<Vec2> bow{{0, 0}, {1, 1}, {1, 0}, {0, 1}};
  EXPECT_NE(first_self_intersection(bow).first, -1);
}

TEST(Kinematics, ExactRotationKeepsDistances) {
  // A rotation of 0.3 rad about the centroid must keep the distance of a point to it;
  // the first-order map T D would stretch it by sqrt(1 + 0.09).
  const Vec2 c(1.0, 2.0), p(3.0, 2.5);
  Vec6 d = Vec6::Zero();
  d[2] = 0.3;
  const Vec2 moved = p + exact_point_displacement(p, c, d);
  EXPECT_NEAR((moved - c).norm(), (p - c).norm(), 1e-14);
  const Vec2 first_order = p + displacement_matrix(p, c) * d;
  EXPECT_GT((first_order - c).norm(), (p - c).norm() * 1.04);
}

TEST(Kinematics, TransposeProductMatchesMatrix) {
  const Vec2 c(0.3, -0.2), p(1.7, 0.9), w(2.0, -1.5);
  const Vec6 direct = displacement_matrix(p, c).transpose() * w;
  EXPECT_LT((direct - displacement_matrix_transpose_times(p, c, w)).norm(), 1e-14);
}

}  // namespace
}  // namespace ddafit
