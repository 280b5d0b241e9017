#include "forward/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/kinematics.hpp"

namespace ddafit {

double signed_area(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  const size_t n = polygon.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2& a = polygon[k];
    const Vec2& b = polygon[(k + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

PolygonMoments polygon_moments(const std::vector<Vec2>& polygon) {
  // Shoelace sums about a local origin (the first vertex) to limit round-off for
  // polygons far from the global origin, then shifted to the centroid.
  PolygonMoments m;
  const size_t n = polygon.size();
  if (n < 3) return m;
  const Vec2 o = polygon[0];
  double a2 = 0.0, cx = 0.0, cy = 0.0, ixx = 0.0, iyy = 0.0, ixy = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const Vec2 p = polygon[k] - o;
    const Vec2 q = polygon[(k + 1) % n] - o;
    const double c = p.x() * q.y() - q.x() * p.y();
    a2 += c;
    cx += (p.x() + q.x()) * c;
    cy += (p.y() + q.y()) * c;
    ixx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * c;  // integral x^2
    iyy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * c;  // integral y^2
    ixy += (p.x() * q.y() + 2.0 * p.x() * p.y() + 2.0 * q.x() * q.y() + q.x() * p.y()) * c;
  }
  m.area = 0.5 * a2;
  if (m.area == 0.0) return m;
  const double gx = cx / (3.0 * a2);
  const double gy = cy / (3.0 * a2);
  m.centroid = o + Vec2(gx, gy);
  // Parallel-axis shift from the local origin to the centroid.
  m.s_xx = ixx / 12.0 - m.area * gx * gx;
  m.s_yy = iyy / 12.0 - m.area * gy * gy;
  m.s_xy = ixy / 24.0 - m.area * gx * gy;
  return m;
}

static bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b);
  const double d3 = cross(a, b, c), d4 = cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  if (d1 == 0 && on_segment(c, d, a)) return true;
  if (d2 == 0 && on_segment(c, d, b)) return true;
  if (d3 == 0 && on_segment(a, b, c)) return true;
  if (d4 == 0 && on_segment(a, b, d)) return true;
  return false;
}

std::pair<int, int> first_self_intersection(const std::vector<Vec2>& polygon) {
  const int n = static_cast<int>(polygon.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
      if (adjacent) continue;
      if (segments_intersect(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n]))
        return {i, j};
    }
  }
  return {-1, -1};
}

double least_width(std::span<const Vec2> polygon) {
  const size_t n = polygon.size();
  double width = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 p = polygon[k], edge = polygon[(k + 1) % n] - p;
    const double length = edge.norm();
    if (length <= 0.0) continue;
    double farthest = 0.0;
    for (const Vec2& q : polygon) farthest = std::max(farthest, std::abs(cross2(edge, q - p)) / length);
    width = std::min(width, farthest);
  }
  return width;
}

bool point_in_polygon(const Vec2& p, std::span<const Vec2> polygon) {
  bool inside = false;
  const size_t n = polygon.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_boundary(const Vec2& p, const std::vector<Vec2>& polygon) {
  double best = std::numeric_limits<double>::infinity();
  const size_t n = polygon.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2& a = polygon[k];
    const Vec2& b = polygon[(k + 1) % n];
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

bool polygons_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tolerance) {
  // A vertex deeper than the tolerance inside the other polygon.
  for (const Vec2& p : a)
    if (point_in_polygon(p, b) && distance_to_boundary(p, b) > tolerance) return true;
  for (const Vec2& p : b)
    if (point_in_polygon(p, a) && distance_to_boundary(p, a) > tolerance) return true;
  // An edge midpoint deeper than the tolerance inside the other polygon: catches blocks
  // that share the lines of two edges and overlap between them, where every vertex
  // lies on the other's boundary and no edges cross properly.
  const auto midpoint_inside = [tolerance](const std::vector<Vec2>& p, const std::vector<Vec2>& q) {
    for (size_t k = 0; k < p.size(); ++k) {
      const Vec2 m = 0.5 * (p[k] + p[(k + 1) % p.size()]);
      if (point_in_polygon(m, q) && distance_to_boundary(m, q) > tolerance) return true;
    }
    return false;
  };
  if (midpoint_inside(a, b) || midpoint_inside(b, a)) return true;
  // A proper crossing of two edges (touching along shared edges is allowed).
  const size_t na = a.size(), nb = b.size();
  for (size_t i = 0; i < na; ++i) {
    const Vec2& p = a[i];
    const Vec2& q = a[(i + 1) % na];
    for (size_t j = 0; j < nb; ++j) {
      const Vec2& r = b[j];
      const Vec2& s = b[(j + 1) % nb];
      const double d1 = cross(r, s, p), d2 = cross(r, s, q);
      const double d3 = cross(p, q, r), d4 = cross(p, q, s);
      const double scale_ab = (q - p).norm() * tolerance;
      const double scale_rs = (s - r).norm() * tolerance;
      if (((d1 > scale_rs && d2 < -scale_rs) || (d1 < -scale_rs && d2 > scale_rs)) &&
          ((d3 > scale_ab && d4 < -scale_ab) || (d3 < -scale_ab && d4 > scale_ab)))
        return true;
    }
  }
  // Identical or nested polygons without deep vertices: compare centroids.
  const PolygonMoments ma = polygon_moments(a), mb = polygon_moments(b);
  if (point_in_polygon(ma.centroid, b) && distance_to_boundary(ma.centroid, b) > tolerance &&
      point_in_polygon(mb.centroid, a) && distance_to_boundary(mb.centroid, a) > tolerance)
    return true;
  return false;
}

double polyline_height(const std::vector<Vec2>& line, double x) {
  if (line.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (x <= line.front().x()) return line.front().y();
  if (x >= line.back().x()) return line.back().y();
  const auto hi = std::upper_bound(line.begin(), line.end(), x, [](double v, const Vec2& p) { return v < p.x(); });
  const Vec2& a = *(hi - 1);
  const Vec2& b = *hi;
  return a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
}

}  // namespace ddafit
