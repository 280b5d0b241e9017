#include "forward/contact/corner_paths.hpp"

#include <algorithm>
#include <array>

#include "forward/contact/manifold.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {
namespace {

// The corners of a piece moved rigidly by `move` about its block's centroid, into `out`
// (reused: pieces seldom have more than a handful of corners).
void moved_corners(const BlockSystem& s, const ContactShapes& shapes, int piece, const Vec3& move,
                   std::vector<Vec2>& out) {
  const ConvexPiece& c = shapes.pieces[piece];
  const Vec2 centroid = s.blocks[c.block].centroid;
  out.resize(c.count);
  for (int i = 0; i < c.count; ++i) {
    const Vec2& v = s.vertices[shapes.corners[c.first + i]];
    out[i] = v + velocity_at(move, v - centroid);
  }
}

// Whether the segment from `from` along `path` enters the counter-clockwise convex polygon
// grown by `grow` (Cyrus-Beck: the segment clipped against each face's half-plane).
bool path_enters(const std::vector<Vec2>& polygon, const Vec2& from, const Vec2& path, double grow) {
  double enter = 0.0, leave = 1.0;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 edge = polygon[(i + 1) % n] - polygon[i];
    const double length = edge.norm();
    if (!(length > 0.0)) continue;
    const Vec2 normal(edge.y() / length, -edge.x() / length);  // outward
    const double outside = normal.dot(from - polygon[i]) - grow;  // > 0: outside this face's line
    const double rate = normal.dot(path);
    if (rate == 0.0) {
      if (outside > 0.0) return false;
    } else if (rate < 0.0) {
      enter = std::max(enter, -outside / rate);
    } else {
      leave = std::min(leave, -outside / rate);
    }
    if (enter > leave) return false;
  }
  return true;
}

}  // namespace

bool apart_corners(const ContactManifold& m, const ContactPoint& p) {
  return m.point_count == 1 && (p.id & kManifoldIdVertexVertex) && p.separation > 0.0 && m.piece_a >= 0 &&
         m.piece_b >= 0;
}

bool corners_pass(const BlockSystem& s, const ContactShapes& shapes, const ContactManifold& m, const ContactPoint& p,
                  double separation, const Vec3& move_a, const Vec3& move_b, const Vec3& rate_a, const Vec3& rate_b,
                  double interval, double grow) {
  thread_local std::vector<Vec2> piece_a, piece_b;
  // The two corners about their centroids at detection: the point lies midway.
  const Vec2 ra = p.ra - 0.5 * separation * m.normal, rb = p.rb + 0.5 * separation * m.normal;
  const Vec2 centroid_a = s.blocks[m.block_a].centroid, centroid_b = s.blocks[m.block_b].centroid;
  const Vec2 corner_a = centroid_a + ra + velocity_at(move_a, ra);
  const Vec2 corner_b = centroid_b + rb + velocity_at(move_b, rb);
  const Vec2 now_a = centroid_a + Vec2(move_a.x(), move_a.y()), now_b = centroid_b + Vec2(move_b.x(), move_b.y());
  const Vec2 path_b = interval * (velocity_at(rate_b, corner_b - now_b) - velocity_at(rate_a, corner_b - now_a));
  const Vec2 path_a = interval * (velocity_at(rate_a, corner_a - now_a) - velocity_at(rate_b, corner_a - now_b));
  moved_corners(s, shapes, m.piece_a, move_a, piece_a);
  if (path_enters(piece_a, corner_b, path_b, grow)) return false;
  moved_corners(s, shapes, m.piece_b, move_b, piece_b);
  return !path_enters(piece_b, corner_a, path_a, grow);
}

}  // namespace ddafit
