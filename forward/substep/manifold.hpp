// Contact manifold between two convex polygons: the one or two points, with a shared
// normal, at which the substep solver applies non-penetration and friction.
// The idea comes from Box2D v3's manifold (separating axis, reference face, clipping);
// the code is our own.
#pragma once

#include <cstdint>
#include <span>

#include "forward/scene.hpp"

namespace ddafit {

struct ManifoldPoint {
  Vec2 point = Vec2::Zero();   // world position: midway between the incident vertex and the reference face
  double separation = 0.0;     // along the normal, m; negative = penetration
  std::uint32_t id = 0;        // feature key: equal ids in successive calls mean the same pair of features
  int owner = -1;              // 0 if the point sits on a vertex of polygon a, 1 if of polygon b (the "overriding" vertex)
  int vertex = -1;             // index of that vertex in its polygon
};

struct Manifold {
  Vec2 normal = Vec2::Zero();  // unit, pointing from a towards b
  int point_count = 0;         // 0, 1 or 2
  ManifoldPoint points[2];
};

// Layout of ManifoldPoint::id. A vertex-face point: bit 30 = owner, bits 15-29 = the
// owner's vertex, bits 0-14 = first edge of the other polygon's face (the face is that
// edge plus any collinear edges after it). A vertex-vertex point additionally sets bit 31
// and stores the other polygon's vertex in bits 0-14. The key does not depend on which
// polygon was the reference, so it survives the reference flipping between a and b.
// Polygons are limited to 32768 vertices.
constexpr std::uint32_t kManifoldIdVertexVertex = 1u << 31;
constexpr std::uint32_t manifold_id(int owner, int vertex, int other_feature, bool vertex_vertex) {
  return (vertex_vertex ? kManifoldIdVertexVertex : 0u) | (static_cast<std::uint32_t>(owner) << 30) |
         (static_cast<std::uint32_t>(vertex) << 15) | static_cast<std::uint32_t>(other_feature);
}

// Convex counter-clockwise polygons a and b. Points are kept while their separation is
// below max_distance (the speculative margin, > 0); where a piece has cuts, only while their
// overlap is below max_depth (default: max_distance; see "Solid edges"). `linear_slop` (m, small, e.g. 1e-4 x
// block size) is the tolerance of the separating-axis comparisons: b becomes the
// reference polygon only when its best axis separates by more than a's by 0.1 x linear_slop
// (a bias against flipping between equal axes). When the polygons are apart by more than
// 0.1 x linear_slop and the closest features of the reference and incident edges are two
// vertices, the manifold has one point with the normal along the line joining the two corners
// (vertex-vertex branch) -- this is what makes corner-to-corner contact have a single normal.
//
// Faces: consecutive edges whose vertices lie within 1e-3 x linear_slop of one line act as
// one face (reference or incident), so a straight vertex in the middle of a side never
// halves the contact; the points sit at the face's end corners.
// Parallel faces: when the two faces are parallel (within 1e-5 rad) and overlap along
// the face, the contact is a face contact (two clipped points) even if the gap is open;
// only faces that do not overlap give the vertex-vertex point.
//
// Solid edges: a convex piece of a concave block has edges that run inside the block
// (the cuts of its decomposition). Such an edge is no face: a neighbour can only be
// across it by overlapping the block's other pieces, and taking it as the reference face
// pushed neighbours into the block (0.5 m deep on Vajont section I). `a_solid[i]` /
// `b_solid[i]` false marks edge i (vertex i to i + 1) as such a cut: it is never a
// reference face or an incident face. It only counts as a separating axis to rule a
// contact out: the other polygon wholly beyond a cut gives no manifold (it lies over or
// beside the block's other pieces, whose own manifolds hold it). A piece whose edges turned
// towards the reference face are all cuts has no incident face there; with `flip_for_cuts`
// the other polygon's best face is then the reference, or there is no contact if that fails
// the same way. The narrow phase asks for it when one of the blocks is fixed (the bedrock
// and the banks, concave and cut into pieces), where a lost contact lets a block fall through
// the model; between two free blocks it made Vajont sections VIII and X overlap by a third of
// a block (2 of 20 runs failed), and there the old reading stays.
// Empty spans: every edge is solid. Where a
// polygon has cuts, points deeper than max_distance are dropped: no step moves a block
// that far into another, and such a point is a corner read across a cut, inside the
// block (one read 18 m "deep" on Vajont section I).
Manifold collide_polygons(std::span<const Vec2> a, std::span<const Vec2> b, double max_distance,
                          double linear_slop, std::span<const char> a_solid = {},
                          std::span<const char> b_solid = {}, double max_depth = -1.0,
                          bool flip_for_cuts = true);

}  // namespace ddafit
