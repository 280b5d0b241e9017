// Convex decomposition of a block's polygon, so that contact detection can work on
// convex pieces only (the manifold of manifold.hpp needs convex polygons).
#pragma once

#include <span>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

// Splits a simple counter-clockwise polygon into convex pieces for contact detection: cuts
// from each reflex corner (the most reflex first) to the vertex that leaves the largest
// smallest angle at the cut's ends, preferring cuts that leave the corner convex on both
// sides, so no piece is a sliver the block's own shape does not force (a contact read on
// a sliver whose one solid face is far from the touching corner is deep and false); then
// Hertel-Mehlhorn removal of every cut whose removal keeps both sides convex. Each piece
// lists indices into `polygon`, counter-clockwise. If round-off hides every cut, it falls
// back to ear clipping (fattest ear first) and Hertel-Mehlhorn.
// A convex polygon (collinear vertices allowed, within a relative tolerance) comes back
// as one piece with all its indices in order. Never throws on a simple polygon; for a
// degenerate input (fewer than 3 vertices, zero area) returns an empty vector.
//
// Tolerance: a vertex closer than 1e-9 x (largest bounding-box side) to the line through
// its neighbours counts as straight. A cut may end at one; the ear-clipping fallback
// leaves them out of the triangulation and puts them back afterwards into the piece that
// holds their edge. Every input vertex is in exactly one piece's boundary walk (or in
// several, if it is a cut's end) and the pieces tile the polygon exactly; a piece can
// therefore be non-convex by at most that tolerance. A clockwise polygon is accepted too:
// its pieces still come out counter-clockwise.
std::vector<std::vector<int>> convex_pieces(std::span<const Vec2> polygon);

}  // namespace ddafit
