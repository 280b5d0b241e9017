// The manifold's "Flush neighbours" rule (forward/contact/manifold.hpp, docs/theory.md §3):
// a block lying beside the end of a face, along its line, touches that face's polygon only in
// a corner sliver and gets no contact; a block that lies along another face of the polygon
// does touch it. Swept over kink angles, block sizes, resting overlaps and joint angles.
// Then "Proud edges": swept over slopes, block sizes, heights of the edge, how far the corner
// has crossed, and both orders of the pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "forward/contact/manifold.hpp"

namespace ddafit {
namespace {

const Vec2 kFar(2400.0, 700.0);  // Vajont-like coordinates
constexpr double kDegree = M_PI / 180.0;
constexpr double kFlushRatio = 0.02;  // collide.hpp's default: eta = 2 % of the block's size

// flush_faces: as collide() sets it for every pair (since model revision 2026-12-07.3; until
// then for pairs with a fixed block only); off, the whole polygon must lie beside a face.
ManifoldSettings flush_settings(double size, bool flush_faces = true) {
  ManifoldSettings m;
  m.flush_faces = flush_faces;
  m.max_distance = 0.05 * size;
  m.linear_slop = 1e-4 * size;
  m.flush_tolerance = kFlushRatio * size;
  return m;
}

// A square of side s whose bottom face lies along the line through `origin` with unit
// tangent t (normal n = t turned left), from u0 to u0 + s along it, sunk d below the line.
std::vector<Vec2> square_on(const Vec2& origin, const Vec2& t, double u0, double s, double d) {
  const Vec2 n(-t.y(), t.x());
  std::vector<Vec2> q;
  for (const auto& [u, v] : {std::pair{u0, -d}, {u0 + s, -d}, {u0 + s, s - d}, {u0, s - d}})
    q.push_back(origin + u * t + v * n);
  return q;
}

// A convex piece whose top is two faces meeting at K = kFar with a slight convex kink: T,
// level, left of K; N, falling at `kink` to the right of K, ten metres each. Their far ends
// lie off each other's line by 10 m x sin(kink), at least 0.087 m, more than the quarter of
// eta (at most 0.055 m, for the 11 m block) within which faces merge into one.
std::vector<Vec2> kinked_piece(double kink) {
  const double L = 10.0;
  return {kFar + Vec2(-L, -20.0), kFar + Vec2(L * std::cos(kink), -20.0),
          kFar + Vec2(L * std::cos(kink), -L * std::sin(kink)), kFar, kFar + Vec2(-L, 0.0)};
}

double deepest(const Manifold& m) {
  double d = 0.0;
  for (int k = 0; k < m.point_count; ++k) d = std::min(d, m.points[k].separation);
  return d;
}

TEST(FlushNeighbours, ABlockOnAFaceBesideASlightKinkOfItsPieceTouchesTheFace) {
  // The block rests on N (or on T) just past the kink, so it also lies beside the other face
  // within eta of its line where the kink is slight enough (0.5-1 deg here; at 2-5 deg the
  // far corner is already beyond eta and the rule never applied). It lies along the face it
  // rests on, so this is no sliver: it must get that face's two points at its own overlap.
  // Before revision 2026-11-27.1 it got none and sank until it left eta (Vajont section V:
  // 20 cm into the bedrock, unseen).
  for (const double kink_degrees : {0.5, 1.0, 2.0, 5.0})
    for (const double s : {0.5, 1.0, 4.0, 11.0})
      for (const double x0 : {0.01, 0.05})
        for (const double overlap : {1e-4, 0.1 * kFlushRatio, 0.5 * kFlushRatio})
          for (const bool on_n : {true, false})
            for (const bool flush_faces : {true, false}) {
              const double kink = kink_degrees * kDegree, d = overlap * s;
              const std::vector<Vec2> piece = kinked_piece(kink);
              // On N: along its tangent from K. On T: the square's far end x0 s short of K.
              const Vec2 t = on_n ? Vec2(std::cos(kink), -std::sin(kink)) : Vec2(1.0, 0.0);
              const std::vector<Vec2> block = square_on(kFar, t, on_n ? x0 * s : -(1.0 + x0) * s, s, d);
              const Manifold m = collide_polygons(piece, block, flush_settings(s, flush_faces));
              SCOPED_TRACE(testing::Message() << "kink " << kink_degrees << " deg, size " << s << " m, x0 " << x0
                                              << ", overlap " << overlap << ", on " << (on_n ? "N" : "T")
                                              << (flush_faces ? "" : ", flush faces off"));
              ASSERT_EQ(m.point_count, 2);
              // The face's outward normal, from the piece towards the block.
              EXPECT_LT((m.normal - Vec2(-t.y(), t.x())).norm(), 1e-9);
              // Both points at the block's overlap: 1e-9 of a block, round-off at 2.4 km.
              for (int k = 0; k < 2; ++k) EXPECT_NEAR(m.points[k].separation, -d, 1e-9 * s + 1e-10);
            }
}

TEST(FlushNeighbours, ABlockSunkIntoTheFaceBeyondAFaceEndIsSeen) {
  // A level block beside the end of a level face T (its left end at T's end), sunk h below
  // T's line, within eta of it: the piece's next face falls at alpha from T's end, so the
  // block's corner is h cos(alpha) deep in the piece along that face's normal, h along T's.
  // That is no sliver and must be reported, at a depth between the two (1e-9 of a block:
  // round-off at 2.4 km). At 45 and 60 deg only the depth guard (eta / 4) sees it; at 10 and
  // 30 deg the block also lies along the falling face.
  for (const double alpha_degrees : {10.0, 30.0, 45.0, 60.0})
    for (const double s : {1.0, 4.0, 11.0})
      for (const double h : {0.6, 0.9}) {
        const double eta = kFlushRatio * s, alpha = alpha_degrees * kDegree, depth = h * eta;
        const Vec2 down = 10.0 * Vec2(std::cos(alpha), -std::sin(alpha));
        const std::vector<Vec2> piece = {kFar + Vec2(-10.0, -40.0), kFar + Vec2(down.x(), -40.0), kFar + down, kFar,
                                         kFar + Vec2(-10.0, 0.0)};
        const std::vector<Vec2> block = square_on(kFar, Vec2(1.0, 0.0), 0.0, s, depth);
        for (const bool flush_faces : {true, false}) {
          SCOPED_TRACE(testing::Message() << "face at " << alpha_degrees << " deg, size " << s << " m, " << h
                                          << " eta below T's line" << (flush_faces ? "" : ", flush faces off"));
          const Manifold m = collide_polygons(piece, block, flush_settings(s, flush_faces));
          ASSERT_GE(m.point_count, 1);
          EXPECT_GE(deepest(m), -depth - 1e-9 * s);
          EXPECT_LE(deepest(m), -depth * std::cos(alpha) + 1e-9 * s);
        }
      }
}

TEST(FlushNeighbours, ABlockRestingOnOneBlockBesideTheNextOfAFlushSurfaceHasNoContactWithIt) {
  // The ghost collision the rule exists for: a slider resting on block A (its resting overlap
  // below the flush surface) with its leading corner at or just short of the joint with
  // block B, whose joint face meets the surface at psi. Its corner lies below B's corner; the
  // separating axis alone would take the joint face or the slider's front face and throw it
  // back. B and the slider touch at most in a sliver: no points. Joints at 60-150 deg to a
  // level surface. (This sweep passes on the old rule too: it guards what the new one keeps.)
  for (const double psi_degrees : {60.0, 75.0, 90.0, 105.0, 120.0, 135.0, 150.0})
    for (const double s : {0.5, 1.0, 4.0, 11.0})
      for (const double overlap : {1e-5, 1e-4})
        for (const double short_of_joint : {0.0, 1e-3}) {
          const double psi = psi_degrees * kDegree;
          const Vec2 down = 5.0 * s * Vec2(std::cos(psi), -std::sin(psi));  // along B's joint face
          const std::vector<Vec2> b = {kFar, kFar + down, kFar + Vec2(10.0 * s, down.y()), kFar + Vec2(10.0 * s, 0.0)};
          const std::vector<Vec2> slider =
              square_on(kFar, Vec2(1.0, 0.0), -(1.0 + short_of_joint) * s, s, overlap * s);
          SCOPED_TRACE(testing::Message() << "joint " << psi_degrees << " deg, size " << s << " m, overlap "
                                          << overlap << ", short " << short_of_joint);
          for (const bool flush_faces : {true, false}) {
            EXPECT_EQ(collide_polygons(b, slider, flush_settings(s, flush_faces)).point_count, 0);
            EXPECT_EQ(collide_polygons(slider, b, flush_settings(s, flush_faces)).point_count, 0);
          }
        }
}

// Face to face (face_axes.cpp, face_to_face): a block tilted over a short block B, hovering
// more than eta above B's top, its base line, extended past its front, passing within eta of
// B's far top corner. B's part near that line lies beside the base, but B's top runs under the
// base: the two are face to face, no neighbours along one line, and the contact is B's top
// against the base, two points, apart (one where the rear's gap is beyond the margin). Before
// model revision 2026-12-07.1 the manifold was empty, and a slider tumbling over a floor
// jointed every 1.3 of its lengths, read so by the block under it, dropped into that block's
// joint with the next (scripts/kink_sweep.py, seed 4: 0.10 m/s left of 5.9 m/s on the whole
// floor). Swept over tilts, sizes, how far the base line passes above the corner, and both
// orders of the pair.
TEST(FlushNeighbours, ABlockTiltedOverAShortBlockTouchesItsTopFace) {
  for (const double tilt_degrees : {0.5, 1.6, 4.0, 8.0})
    for (const double s : {0.1, 1.0, 11.0})
      for (const double passes : {0.3, 0.8}) {  // the base line's height over B's far corner, in eta
        const double tilt = tilt_degrees * kDegree, eta = kFlushRatio * s, above = passes * eta;
        // The slider's front lies where its base line is 1.5 eta above B's top (B's part within
        // eta of the line then begins beyond the front), and its rear 0.2 s inside B's near end.
        const double ahead = (1.5 * eta - above) / std::tan(tilt), length = ahead + 1.2 * s;
        const std::vector<Vec2> b = {kFar + Vec2(0.0, -s), kFar + Vec2(length, -s), kFar + Vec2(length, 0.0), kFar};
        const Vec2 t(std::cos(tilt), -std::sin(tilt));
        const double front = -ahead / std::cos(tilt);
        const std::vector<Vec2> slider = square_on(kFar + Vec2(length, above), t, front - s, s, 0.0);
        for (const bool b_first : {true, false}) {
          SCOPED_TRACE(testing::Message() << "tilt " << tilt_degrees << " deg, size " << s << " m, line "
                                          << passes << " eta above the corner" << (b_first ? "" : ", slider first"));
          const Manifold m = b_first ? collide_polygons(b, slider, flush_settings(s))
                                     : collide_polygons(slider, b, flush_settings(s));
          // The rear end's point only while its gap is within the margin (flush_settings: 0.05 s).
          const int expected = 1.5 * eta + s * std::sin(tilt) < 0.05 * s ? 2 : 1;
          ASSERT_EQ(m.point_count, expected);
          // The normal is B's top's or the base's (from B to the slider either way round).
          const Vec2 up = b_first ? m.normal : Vec2(-m.normal);
          EXPECT_GT(up.y(), std::cos(tilt) - 1e-12);
          // Apart: the gaps under the base's two ends, 1.5 eta at the front and more behind.
          for (int k = 0; k < m.point_count; ++k) {
            EXPECT_GT(m.points[k].separation, 1.4 * eta);
            EXPECT_LT(m.points[k].separation, 1.5 * eta + 1.01 * s * std::sin(tilt));
          }
        }
      }
}

// ... and where B's most opposite face lies along the base line beside it, they stay
// neighbours. A slider that has just passed a convex kink K of a piece, its base along the
// face T before the kink (within eta / 10 of its line), lies over the falling face N, which
// runs under the base (the spanning ground of tests/test_ground_joints.cpp, kink 10 deg).
// Its contact, if any, is with N under it: no point at K or on T, behind its rear corner.
// Reading T as the face under it put a point at K and braked the slider (0.35 of its travel).
TEST(FlushNeighbours, ABlockJustPastAConvexKinkHasNoContactBehindIt) {
  for (const double kink_degrees : {5.0, 10.0, 20.0})
    for (const double s : {0.1, 1.0, 11.0})
      for (const double past : {0.05, 0.1, 0.5})  // the rear corner past K, in slider lengths
        for (const double tilt_share : {0.0, 0.1, 0.5}) {  // the base turned towards N, of the kink
          const double kink = kink_degrees * kDegree, tilt = tilt_share * kink;
          const std::vector<Vec2> piece = kinked_piece(kink);
          const Vec2 t(std::cos(tilt), -std::sin(tilt));
          const std::vector<Vec2> slider = square_on(kFar, t, past * s, s, -1e-3 * kFlushRatio * s);
          for (const bool piece_first : {true, false}) {
            SCOPED_TRACE(testing::Message() << "kink " << kink_degrees << " deg, size " << s << " m, " << past
                                            << " past K, tilt " << tilt_share << (piece_first ? "" : ", slider first"));
            const Manifold m = piece_first ? collide_polygons(piece, slider, flush_settings(s))
                                           : collide_polygons(slider, piece, flush_settings(s));
            for (int k = 0; k < m.point_count; ++k)
              EXPECT_GT((m.points[k].point - kFar).dot(t), past * s - 1e-6 * s) << "a point behind the slider";
          }
        }
}

// "Proud edges" (manifold.hpp): a block whose corner has just crossed a joint onto a neighbour
// that stands proud of the face it rests on by no more than linear_slop touches that neighbour
// through its own face (the one it was held up by), not through the joint's face, also when
// the corner rests up to the slop deep in the blocks behind. A step higher than both together
// (the rule's window, twice the slop) is a step.

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

// As collide() sets a pair of free blocks (flush faces on, as for every pair since model
// revision 2026-12-07.3), with the slop of a run whose largest move per step is 5 % of the block
// ahead (kSlopRatio 1e-3 of it), and both blocks held up by the slope in the last step.
ManifoldSettings free_pair(double w, const Vec2& up) {
  ManifoldSettings m;
  m.flush_faces = true;
  m.max_distance = 0.05 * w;
  m.linear_slop = 5e-5 * w;
  m.flush_tolerance = 0.02 * w;
  m.support_a = up;
  m.support_b = up;
  return m;
}

// The contact of the pair through the face the slider was held up by: the slider's bottom on
// the block ahead's top, normal along the slope's normal (1e-9: round-off at 2.4 km), `depth`
// deep.
void expect_held_up_face(const ProudEdge& e, double w, bool slider_first, double depth) {
  const ManifoldSettings ms = free_pair(w, e.up);
  const Manifold m = slider_first ? collide_polygons(e.slider, e.ahead, ms) : collide_polygons(e.ahead, e.slider, ms);
  ASSERT_GE(m.point_count, 1);
  const Vec2 expected = slider_first ? Vec2(-e.up) : e.up;  // from a towards b
  EXPECT_LT((m.normal - expected).norm(), 1e-9);
  EXPECT_NEAR(deepest(m), -depth, 1e-9 * w + 1e-10);
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
            expect_held_up_face(e, w, slider_first, proud);
          }
}

TEST(ProudEdges, ACornerRestingDeepMeetsAnEdgeProudOfItsSupportsThroughItsOwnFace) {
  // The corner rests 50-100 % of the slop deep in the blocks behind (blocks at rest sit up to
  // the slop deep before the push-out acts) and the edge ahead stands 30-90 % of the slop proud
  // of them; the corner has crossed the joint by 10-90 % of the edge's height. The edge's face
  // overlaps the corner by up to twice the slop, more than the joint's face plus the slop:
  // before revision 2026-12-05.1 the rule asked for that, took the joint's face, and a 1 x 0.5 m
  // slider on a row of 0.1 m cubes at 2 ms x 4 met the first unloaded cube's rear face 9.9 um
  // deep with its own face 51 um deep in the cube's top, and was thrown off the row at 1 m/s
  // (tests/test_free_row.cpp, cube rows at coarser steps).
  int checked = 0;
  for (const double slope : {0.0, 15.0, 35.0})
    for (const double w : {0.15, 1.0, 8.2})
      for (const double rest_share : {0.5, 1.0})
        for (const double proud_share : {0.3, 0.6, 0.9})
          for (const double crossed_share : {0.1, 0.5, 0.9})
            for (const bool slider_first : {true, false}) {
              const double slop = 5e-5 * w, proud = proud_share * slop, overlap = proud + rest_share * slop;
              const ProudEdge e = proud_edge(slope, w, overlap, crossed_share * proud);
              SCOPED_TRACE(testing::Message() << "slope " << slope << " deg, block " << w << " m, resting "
                                              << rest_share << " slop deep, edge " << proud_share
                                              << " slop proud, crossed " << crossed_share << " of it, slider "
                                              << (slider_first ? "a" : "b"));
              expect_held_up_face(e, w, slider_first, overlap);
              ++checked;
            }
  EXPECT_EQ(checked, 324);
}

TEST(ProudEdges, AStepHigherThanTheWindowStopsTheCorner) {
  // The same corner, resting on the line of the blocks behind, against an edge 60-400 times
  // the slop high: a real step, higher than the rule's window (twice the slop: a corner resting
  // up to the slop deep meeting an edge up to the slop proud) and than the reach of a flush
  // face (eta / 10 = 40 slop here: a corner within it of the line of the edge's face lies
  // against that face, which then holds it, as on a fixed surface, manifold.hpp; between free
  // blocks too since model revision 2026-12-07.3, when this sweep's steps of 2.5 and 10 slop
  // became such edges). Its face is the contact (normal along the slope, back up it), and the
  // depth is how far the corner crossed.
  for (const double slope : {0.0, 15.0, 35.0})
    for (const double w : {0.15, 1.0, 8.2})
      for (const double proud_share : {60.0, 100.0, 400.0})
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

// Four blocks of two layers meeting at one corner on a cut that leans through both (a slab cut
// into columns on a slope): the top layer rests about the slop deep in the bottom one (up to
// 1.5 slop here) and may have sheared forward on it by up to the slop, so the two blocks that
// touch only at that corner (the top rear and bottom front where the cut leans forward) overlap
// there by the resting depth along the layers' face and by a share of it plus the shear along
// the cut's. The contact is the layers' face, through which both blocks are held up, even where
// the overlap along the cut is the smaller one; the cut's face pushed the two columns of the slab
// apart (tests/test_stacked_slider.cpp: 2.2 % off seed Eq. 4 until revision 2026-12-03.5, whose
// "Proud edges" window stopped at one slop; 144 of these 972 cases took the cut's face then).
// Swept over slopes, leans, the scene mirrored (descending to the left), block sizes, resting
// depths and shears up to the slop, and both orders of the pair.
TEST(ProudEdges, AJunctionOfFourBlocksOnALeaningCutTouchesThroughTheLayersFace) {
  int checked = 0;
  for (const double slope : {0.0, 15.0, 35.0})
    for (const double lean : {20.0, 30.0, 45.0})
      for (const bool mirrored : {false, true})
        for (const double w : {0.15, 1.0, 8.2})
          for (const double depth_share : {0.5, 1.0, 1.5})
            for (const double shear_share : {0.0, 0.5, 1.0})
              for (const bool bottom_first : {true, false}) {
                const double slop = 5e-5 * w, depth = depth_share * slop, shear = shear_share * slop;
                const double a = slope * kDegree, l = lean * kDegree;
                const Vec2 along(std::cos(a), -std::sin(a)), up(std::sin(a), std::cos(a));
                const Vec2 cut = std::cos(l) * up + std::sin(l) * along;
                // A block with its rear foot at `o`, w along the slope and `h` up the cut.
                const auto block = [&](const Vec2& o, double h) {
                  std::vector<Vec2> q = {o, o + w * along, o + w * along + h * cut, o + h * cut};
                  if (mirrored) {
                    for (Vec2& v : q) v.x() = 2.0 * kFar.x() - v.x();
                    std::reverse(q.begin(), q.end());  // counter-clockwise again
                  }
                  return q;
                };
                const Vec2 sunk = kFar - depth * up + shear * along;  // the top layer's corner
                const std::vector<Vec2> bottom_front = block(kFar - 0.5 * w * cut, 0.5 * w);
                const std::vector<Vec2> top_rear = block(sunk - w * along, 0.75 * w);
                const Vec2 held_up = mirrored ? Vec2(-up.x(), up.y()) : up;
                SCOPED_TRACE(testing::Message() << "slope " << slope << " deg, cut leaning " << (mirrored ? -lean : lean)
                                                << " deg, block " << w << " m, top layer " << depth_share
                                                << " slop deep, sheared " << shear_share << " slop, bottom block "
                                                << (bottom_first ? "a" : "b"));
                const ManifoldSettings ms = free_pair(w, held_up);
                const Manifold m = bottom_first ? collide_polygons(bottom_front, top_rear, ms)
                                                : collide_polygons(top_rear, bottom_front, ms);
                ASSERT_GE(m.point_count, 1);
                const Vec2 expected = bottom_first ? held_up : Vec2(-held_up);  // from a towards b
                EXPECT_LT((m.normal - expected).norm(), 1e-9);
                EXPECT_NEAR(deepest(m), -depth, 1e-9 * w + 1e-10);
                ++checked;
              }
  EXPECT_EQ(checked, 972);
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
