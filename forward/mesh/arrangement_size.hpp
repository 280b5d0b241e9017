// The mesher's work bound: the size of a region's arrangement, estimated before it is built.
#pragma once

#include <utility>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

using Segment2 = std::pair<Vec2, Vec2>;

// Pair tests allowed per edge of the bound while counting curved crossings: a test costs
// about a hundredth of what CGAL spends per edge, so the count stays a small part of the
// cut it guards.
constexpr double kCountTestsPerEdge = 100.0;

// The pieces one source puts into the arrangement: the region outline, or one joint set's
// traces clipped to the box. A straight set is parallel lines `spacing` apart along `along`.
struct TraceFamily {
  std::vector<Segment2> pieces;
  bool straight = false;
  Vec2 along = Vec2::Zero();  // unit direction of a straight set's lines
  double spacing = 0.0;       // m, between a straight set's lines
};

// Pieces a set will lay across the box [lo, hi] (an upper count, before any is made), so
// a parallel_to polyline of a million points is refused before its copies fill memory.
double planned_trace_pieces(const JointSet& set, double block_size, const Vec2& lo, const Vec2& hi);

// Edges of the arrangement of all the families: pieces + 2 x crossings, with crossings
// against straight sets bounded from the pieces' lengths and directions, and crossings
// among curved pieces counted. Stops refining once the estimate reaches `enough`; returns
// infinity when the curved pieces overlap in more than kCountTestsPerEdge x `enough` pairs (too many to
// count, and a sign of a region far thinner than its box).
double estimated_arrangement_edges(const std::vector<TraceFamily>& families, double enough);

}  // namespace ddafit
