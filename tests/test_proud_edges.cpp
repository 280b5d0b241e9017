// The manifold's "Proud edges" rule (forward/contact/manifold.hpp, docs/theory.md §3): a
// block whose corner has just crossed a joint onto a neighbour that stands proud of the face
// it rests on by no more than linear_slop touches that neighbour through its own face (the
// one it was held up by), not through the joint's face. A step higher than that is a step.
// Swept over slopes, block sizes, heights of the edge, how far the corner has crossed, and
// both orders of the pair.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "forward/contact/manifold.hpp"

namespace ddafit {
namespace {

const Vec2 kFar(2400.0, 700.0);  // Vajont-like coordinates
constexpr double kDegree = M_PI / 180.0;

// A block of the row ahead (length w, thickness 0.75 w) whose top runs along the slope line
// through kFar from the joint (u = 0) on, and a slider (length 3 w, height 1.5 w) resting on
// the blocks behind, `proud` below that line, its front corner `crossed` past the joint.
// Counter-clockwise, in slope coordinates u (down the slope) and v (up from it).
struct ProudEdge {
  std::vector<Vec2> ahead, slider;
  Vec2 up;
};
ProudEdge proud_edge(double slope_degrees, double w, double proud, double crossed) {
  const double a = slope_degrees * kDegree;
  const Vec2 along(std::cos(a), -std::sin(a)), up(std::sin(a), std::cos(a));
  const auto at = [&](double u, double v) { return Vec2(kFar + u * along + v * up); };
  const double h = 0.75 * w, length = 3.0 * w, height = 1.5 * w;
  ProudEdge e;
  e.ahead = {at(0, -h), at(w, -h), at(w, 0), at(0, 0)};
  e.slider = {at(crossed - length, -proud), at(crossed, -proud), at(crossed, height - proud),
              at(crossed - length, height - proud)};
  e.up = up;
  return e;
}

// As collide() sets a pair of free blocks (flush faces off), with the slop of a run whose
// largest move per step is 5 % of the block ahead (kSlopRatio 1e-3 of it), and both blocks
// held up by the slope in the last step.
ManifoldSettings free_pair(double w, const Vec2& up) {
  ManifoldSettings m;
  m.flush_faces = false;
  m.max_distance = 0.05 * w;
  m.linear_slop = 5e-5 * w;
  m.flush_tolerance = 0.02 * w;
  m.support_a = up;
  m.support_b = up;
  return m;
}

double deepest(const Manifold& m) {
  double d = 0.0;
  for (int k = 0; k < m.point_count; ++k) d = std::min(d, m.points[k].separation);
  return d;
}

TEST(ProudEdges, ACornerJustAcrossAJointOntoAProudEdgeTouchesThroughItsOwnFace) {
  // The edge ahead stands 10-90 % of the slop proud, the corner has crossed by 10-90 % of
  // that: the joint face overlaps less than the edge does, so the separating axis alone
  // takes the joint face (the slider held at the joint for good, before revision
  // 2026-12-01.1). The contact must be the slider's bottom against the top of the block
  // ahead: normal along the slope's normal (1e-9: round-off at 2.4 km), depth the edge's.
  for (const double slope : {0.0, 15.0, 35.0, 60.0})
    for (const double w : {0.15, 0.4, 1.0, 8.2})
      for (const double proud_share : {0.1, 0.5, 0.9})
        for (const double crossed_share : {0.1, 0.5, 0.9})
          for (const bool slider_first : {true, false}) {
            const double slop = 5e-5 * w, proud = proud_share * slop;
            const ProudEdge e = proud_edge(slope, w, proud, crossed_share * proud);
            SCOPED_TRACE(testing::Message() << "slope " << slope << " deg, block " << w << " m, edge "
                                            << proud_share << " slop proud, crossed " << crossed_share
                                            << " of it, slider " << (slider_first ? "a" : "b"));
            const ManifoldSettings ms = free_pair(w, e.up);
            const Manifold m = slider_first ? collide_polygons(e.slider, e.ahead, ms)
                                            : collide_polygons(e.ahead, e.slider, ms);
            ASSERT_GE(m.point_count, 1);
            const Vec2 expected = slider_first ? Vec2(-e.up) : e.up;  // from a towards b
            EXPECT_LT((m.normal - expected).norm(), 1e-9);
            EXPECT_NEAR(deepest(m), -proud, 1e-9 * w + 1e-10);
          }
}

TEST(ProudEdges, AStepHigherThanTheSlopStopsTheCorner) {
  // The same corner against an edge 2-100 times the slop high: a real step. Its face is the
  // contact (normal along the slope, back up it), and the depth is how far the corner crossed.
  for (const double slope : {0.0, 15.0, 35.0})
    for (const double w : {0.15, 1.0, 8.2})
      for (const double proud_share : {2.0, 10.0, 100.0})
        for (const bool slider_first : {true, false}) {
          const double slop = 5e-5 * w, proud = proud_share * slop, crossed = 0.5 * slop;
          const ProudEdge e = proud_edge(slope, w, proud, crossed);
          SCOPED_TRACE(testing::Message() << "slope " << slope << " deg, block " << w << " m, step " << proud_share
                                          << " slop high, slider " << (slider_first ? "a" : "b"));
          const ManifoldSettings ms = free_pair(w, e.up);
          const Manifold m = slider_first ? collide_polygons(e.slider, e.ahead, ms)
                                          : collide_polygons(e.ahead, e.slider, ms);
          ASSERT_GE(m.point_count, 1);
          const double a = slope * kDegree;
          const Vec2 along(std::cos(a), -std::sin(a));
          const Vec2 expected = slider_first ? along : Vec2(-along);
          EXPECT_LT((m.normal - expected).norm(), 1e-9);
          EXPECT_NEAR(deepest(m), -crossed, 1e-9 * w + 1e-10);
        }
}

TEST(ProudEdges, WithoutSupportsTheSeparatingAxisStands) {
  // No step has run yet (no supports): nothing tells which face held the blocks up, and the
  // separating axis decides, as before the rule (the joint's face, the shallower overlap).
  const double w = 1.0, slop = 5e-5 * w, proud = 0.5 * slop;
  const ProudEdge e = proud_edge(15.0, w, proud, 0.5 * proud);
  ManifoldSettings ms = free_pair(w, e.up);
  ms.support_a = ms.support_b = Vec2::Zero();
  const Manifold m = collide_polygons(e.slider, e.ahead, ms);
  ASSERT_GE(m.point_count, 1);
  EXPECT_NEAR(deepest(m), -0.5 * proud, 1e-9);
}

}  // namespace
}  // namespace ddafit
