// Polygon geometry used by the block system and the scene checks.
#pragma once

#include <span>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

// Area moments of a simple polygon. Second moments are about the centroid:
// s_xx = integral of X^2 dA, s_yy = integral of Y^2 dA, s_xy = integral of X Y dA,
// with X = x - x0, Y = y - y0 (the integrals of DDA's mass matrix, Shi 1993 ch. 2).
struct PolygonMoments {
  double area = 0.0;  // signed: positive for counter-clockwise order
  Vec2 centroid = Vec2::Zero();
  double s_xx = 0.0;
  double s_yy = 0.0;
  double s_xy = 0.0;
};

PolygonMoments polygon_moments(const std::vector<Vec2>& polygon);

double signed_area(const std::vector<Vec2>& polygon);

// z of a polyline (x increasing) at x by linear interpolation, flat beyond its ends; NaN
// for an empty line (water tables, surveyed surfaces).
double polyline_height(const std::vector<Vec2>& line, double x);

// Twice the signed area of triangle (a, b, c): > 0 when c lies left of a->b.
inline double cross(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// True when closed segments [a, b] and [c, d] share a point.
bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

// Index pair of the first two non-adjacent edges that intersect, or {-1, -1} when the
// polygon is simple. Quadratic in the vertex count of one polygon, which is small.
std::pair<int, int> first_self_intersection(const std::vector<Vec2>& polygon);

// Strict interior test (even-odd rule); points on the boundary count as outside
// unless within `tolerance` of it is requested as inside via the return of
// distance_to_boundary().
bool point_in_polygon(const Vec2& p, std::span<const Vec2> polygon);
// Least width of a polygon: over its edges, the farthest corner from the edge's line (exact for a
// convex one: the narrowest strip that holds it). Infinite without a non-degenerate edge.
double least_width(std::span<const Vec2> polygon);
double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& polygon);

// Area of the intersection of two simple polygons would need clipping; for overlap
// checks we use: any proper edge crossing, or a vertex of one deeper than
// `tolerance` inside the other.
bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tolerance);

}  // namespace ddafit
