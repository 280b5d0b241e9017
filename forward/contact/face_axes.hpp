// The faces of a convex polygon as separating axes, and what the flush rules of
// manifold.hpp ("Flush neighbours", "Flush faces") read from them: the narrow phase's first
// half (collide_polygons in manifold.cpp is the second: reference and incident faces,
// clipping). Internal to the contact stage.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <span>
#include <vector>

#include "forward/contact/manifold.hpp"
#include "forward/kinematics.hpp"
#include "forward/scene.hpp"

namespace ddafit::face_axes {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Outward direction of an edge of a counter-clockwise polygon: its right-hand side.
inline Vec2 outward(const Vec2& edge) { return Vec2(edge.y(), -edge.x()); }

// A polygon seen from a's first vertex: the polygons are metres across but their
// coordinates reach ~3000 m, so differences are taken once, near the origin. `v` holds the
// n vertices less the origin twice over (make_shape), so a vertex i in [0, 2n) is read
// without a wrap or a subtraction: the narrow phase reads each vertex many times per pair
// (every edge of the other polygon), and the wrap by % was a tenth of it.
struct Shape {
  std::span<const Vec2> v;
  Vec2 origin;
  int n = 0;
  const Vec2& at(int i) const { return v[static_cast<size_t>(i)]; }
};

// The storage of a Shape's doubled vertices: on the stack for up to kInline vertices.
struct ShapeStore {
  static constexpr size_t kInline = 16;
  std::array<Vec2, 2 * kInline> inline_vertices;
  std::vector<Vec2> more;
};
inline Shape make_shape(std::span<const Vec2> vertices, const Vec2& origin, ShapeStore& store) {
  const size_t n = vertices.size();
  Vec2* out = store.inline_vertices.data();
  if (n > ShapeStore::kInline) {
    store.more.resize(2 * n);
    out = store.more.data();
  }
  for (size_t i = 0; i < n; ++i) out[i] = out[i + n] = vertices[i] - origin;
  return Shape{std::span<const Vec2>(out, 2 * n), origin, static_cast<int>(n)};
}

struct Axis {
  int edge = -1;                   // the best axis that may be a reference face (long enough)
  double separation = -kInfinity;  // its separation
  double apart = -kInfinity;       // the best separation over every solid axis (cuts are no axis here)
  bool flush_beside = false;       // "Flush neighbours" (manifold.hpp) holds for one of p's faces
  // q lies along one of p's faces: its part within kRideDepth x eta of the face's line (or
  // below it) reaches more than eta along the face. The two touch there, whatever another
  // face's line says: they are no sliver (collide_polygons).
  bool rides = false;
  // "Flush faces" (manifold.hpp): of the faces of p whose line q lies against (its gap
  // within eta / 10 on either side), the best (flush_better); -1 if none. A face q lies
  // beside is a candidate too; it matters only where the pair is no sliver (collide_polygons).
  int flush_edge = -1;
  double flush_gap = kInfinity;
  double flush_support = 0.0;  // how well its normal agrees with the pair's supports
  // Its line carries a corner of q that touched a face of the same direction in the last step, q
  // not face to face with it: it continues the surface that corner slides on, and ranks before
  // the supports (flush_better).
  bool flush_slides = false;
};

// Flush faces are ranked by how well their normal (from p towards q) agrees with the way
// the two blocks were held up in the last step (ManifoldSettings::support_*): a block that
// rests on a surface meets the next block of it through its face, not its side, when its
// corner crosses the joint. Only while both gaps are within kRideDepth x eta: a corner
// deeper under a face has met a step, whose side is the contact (a block riding up a 2 mm
// step under a 1.2 m block was kicked off it by the implicit solver's penalty spring).
// Otherwise, and within kSupportTie of each other, the face q lies closer to the line of
// (least |gap|). Before all these, a face that continues the surface a corner of q slid on in the
// last step (Axis::flush_slides).
inline constexpr double kSupportTie = 0.05;
inline constexpr double kRideDepth = 0.1;
// "Flush neighbours" (manifold.hpp) empties the manifold of a corner sliver: a pair whose
// separation over every solid axis is no deeper than this share of eta. A quarter: a block
// resting on a flush surface overlaps it by its resting overlap (about 1e-4 of its size, 1/200
// of eta at the default ratio), and a quarter of eta is half the 1 % overlap the runs are held to.
inline constexpr double kSliverDepth = 0.25;
struct FlushRank {
  bool slides = false;
  double support = 0.0;
  double gap = kInfinity;
};
bool flush_better(const FlushRank& face, const FlushRank& than, double eta, double slop);

// The edge of `inc` facing the direction `normal` (unit) the most, among its solid edges:
// the incident face. `facing` is the cosine between its outward normal and `normal`;
// -1 is face to face. A convex polygon always has an edge with facing < 0; only a piece
// whose edges turned that way are all cuts can give facing > 0.
struct Incident {
  int edge = -1;
  double facing = kInfinity;
};

Incident incident_edge(const Shape& inc, std::span<const char> solid, const Vec2& normal, double tiny);

// A face: the run of edges from vertex `first` to vertex `last` (counter-clockwise).
struct Face {
  int first = 0;
  int last = 0;
};

// Grows an edge over its neighbours while they continue its line within `flat`. Without
// this a straight vertex in the middle of a side would make the reference face half a
// side, and a block resting on that side would be held at one half only.
Face grow_face(const Shape& p, int edge, double flat);

// The span along a face's line of the part of q within eta of the line, or below it:
// q clipped to the band h <= eta, h = normal . (x - p0). Its vertices in the band and
// the points where its edges leave the band, projected on the tangent from p0.
struct Span {
  double lo, hi;
};
Span near_line_span(const Shape& q, const Vec2& p0, const Vec2& normal, const Vec2& tangent, double eta);

// The length of edge i of p grown over its collinear neighbours (grow_face).
double face_length(const Shape& p, int i, double flat);

// The edge of p whose normal separates q from p the most. p's own extent beyond the
// edge along that normal is subtracted: it is zero for a convex polygon, but keeps the
// value a true lower bound of the gap if a nearly straight vertex leaves a tiny edge
// whose normal points anywhere. Stops early once the separation passes `apart` (no
// contact then; the caller only needs to know that).
// With eta > 0 it also reads the faces q lies against (its gap within eta on either
// side; manifold.hpp, "Flush neighbours" and "Flush faces"): the gap is at hand, and only
// such faces need q's span along them.
struct AxisLimits {
  double tiny = 0.0;   // an edge shorter than this has no direction
  double apart = 0.0;  // the margin beyond which there is no contact
  double eta = 0.0;    // the flush tolerance
  double flat = 0.0;   // a face's straightness (grow_face)
  bool flush_faces = true;  // ManifoldSettings::flush_faces
  // The supports of p's and q's blocks (ManifoldSettings::support_a/b): a normal from p
  // towards q agrees with q's support, or against p's.
  Vec2 support_p = Vec2::Zero(), support_q = Vec2::Zero();
  CornerHolds held_q;  // the faces q's corners touched in the last step (ManifoldSettings::held_*)
};
// How well a face normal of p (from p towards q) agrees with the supports of the last step:
// it points the way q's block was pushed, or against p's.
inline double support_agreement(const Vec2& normal, const AxisLimits& limits) {
  return std::max(normal.dot(limits.support_q), -normal.dot(limits.support_p));
}
// `reflex` and `q_reflex` mark the corners that are reflex corners of their blocks (empty:
// none): q beside such an end of a face, or with such a corner near the face's line, is no
// flush neighbour. Nor is q whose face most nearly opposite to the face (of its solid edges,
// `q_solid`) runs under it for more than eta: the two are face to face (face_axes.cpp).
Axis best_axis(const Shape& p, std::span<const char> solid, std::span<const char> reflex, const Shape& q,
               std::span<const char> q_solid, std::span<const char> q_reflex, const AxisLimits& limits);

// "Proud edges" (manifold.hpp): of p's faces that may be a reference face (solid, at least
// eta long) and that q overlaps by no more than `depth` (separation in [-depth, 0]), the one
// whose normal (from p towards q) agrees best with the supports (limits.support_p/q); edge -1
// if none. Asked only of a pair that overlaps that little along every axis.
struct ProudFace {
  int edge = -1;
  double separation = -kInfinity;
  double support = -kInfinity;
};
ProudFace proud_face(const Shape& p, std::span<const char> solid, const Shape& q, const AxisLimits& limits,
                     double depth);

// "Kink corners" (manifold.hpp): of q's corners that lie ahead of p on the line of a face p rests
// on (its outward normal against `rest_p` by more than kRestsOn) -- within eta / 10 of the line,
// beyond the face's end by less than `reach`, both faces of q there solid -- where a face of q at
// least eta long turns up from the line (into p's side, by a sine of more than kKinkSine and by
// less than 60 deg) and runs on away from the face's end while q's other face there goes down
// below the line: the one nearest the face's end, that face of q and p's corner at that end;
// corner -1 if none.
// cos 5 deg: a block resting on a face lies along it (its support is the face's normal to
// within round-off and its rocking); a voussoir of a falling arch, held at a corner by its
// neighbour's extrados 26 deg off its intrados, does not rest on its intrados.
inline constexpr double kRestsOn = 0.996;
inline constexpr double kKinkSine = 1e-3;
// tan 60 deg: a face turning up more steeply is a wall, which the resting polygon's front face
// meets face to face (the separating axis reads that): read as a kink, a block driven along a
// floor into a row of blocks met the first one's side (tilted by micro-radians) at its corner
// alone, and rebounded.
inline constexpr double kKinkSteepest = 1.7320508075688772;
struct KinkCorner {
  int corner = -1;  // of q
  int face = -1;    // q's edge that turns up there
  int end = -1;     // p's corner at the end of the face it rests on, on the corner's side
  double beyond = kInfinity;
};
KinkCorner kink_corner(const Shape& p, std::span<const char> p_solid, const Vec2& rest_p, const Shape& q,
                       std::span<const char> q_solid, double eta, double flat, double reach);

// True when some cut of p (solid[i] false; manifold.hpp, "Solid edges") has q wholly beyond
// it, within slop.
bool cut_separates(const Shape& p, const Shape& q, double tiny, std::span<const char> solid, double slop);

}  // namespace ddafit::face_axes
