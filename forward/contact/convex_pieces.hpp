// Convex decomposition of a block's polygon, so that contact detection can work on
// convex pieces only (the manifold of manifold.hpp needs convex polygons).
#pragma once

#include <span>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

// Splits a simple counter-clockwise polygon into convex pieces for contact detection:
// ear-clipping triangulation, then Hertel-Mehlhorn removal of every diagonal whose removal
// keeps both sides convex. Each piece lists indices into `polygon`, counter-clockwise.
// A convex polygon (collinear vertices allowed, within a relative tolerance) comes back
// as one piece with all its indices in order. Never throws on a simple polygon; for a
// degenerate input (fewer than 3 vertices, zero area) returns an empty vector.
//
// Tolerance: a vertex closer than 1e-9 x (largest bounding-box side) to the line through
// its neighbours counts as straight. Such vertices are left out of the triangulation and
// put back afterwards into the piece that holds their edge, so every input vertex is in
// exactly one piece's boundary walk (or in several, if it is a diagonal's end) and the
// pieces tile the polygon exactly; a piece can therefore be non-convex by at most that
// tolerance. A clockwise polygon is accepted too: its pieces still come out
// counter-clockwise.
std::vector<std::vector<int>> convex_pieces(std::span<const Vec2> polygon);

}  // namespace ddafit
