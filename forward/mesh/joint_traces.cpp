#include <algorithm>
#include <cmath>

#include "forward/mesh/region.hpp"

namespace ddafit {
namespace {

// Intersection of the lines p + s u and q + t v (not parallel).
Vec2 line_intersection(const Vec2& p, const Vec2& u, const Vec2& q, const Vec2& v) {
  const double det = u.x() * v.y() - u.y() * v.x();
  const double s = ((q - p).x() * v.y() - (q - p).y() * v.x()) / det;
  return p + s * u;
}

// Offset joins reach at most this multiple of the offset distance from the corner (the
// "miter limit" of drawing programs). At a corner that turns by alpha the mitre lies
// distance / cos(alpha / 2) away: a turn of 150 deg gives 3.9 x, a spike that turns
// nearly back on itself gives thousands, and every copy of it then crosses the region.
constexpr double kMiterLimit = 4.0;

// The polyline offset by `distance` along its left normal (upwards for a polyline
// ordered by increasing x): each segment is shifted and neighbours are joined at the
// intersection of their shifted lines, or cut off square (a bevel) where that would pass
// the mitre limit; the end segments run on to the box.
std::vector<Vec2> offset_polyline(const std::vector<Vec2>& line, double distance, double reach) {
  std::vector<Vec2> points, directions;
  for (size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec2 u = (line[k + 1] - line[k]).normalized();
    points.push_back(line[k] + distance * Vec2(-u.y(), u.x()));
    directions.push_back(u);
  }
  std::vector<Vec2> out;
  out.push_back(points.front() - reach * directions.front());
  for (size_t k = 1; k < points.size(); ++k) {
    if (std::abs(directions[k - 1].x() * directions[k].y() - directions[k - 1].y() * directions[k].x()) < 1e-12)
      continue;  // collinear neighbours: no corner
    const Vec2 join = line_intersection(points[k - 1], directions[k - 1], points[k], directions[k]);
    if ((join - line[k]).norm() <= kMiterLimit * std::abs(distance)) {
      out.push_back(join);
    } else {
      const Vec2& u = directions[k - 1];
      out.push_back(line[k] + distance * Vec2(-u.y(), u.x()));  // end of the shifted segment before
      out.push_back(points[k]);                                  // start of the shifted segment after
    }
  }
  const Vec2 last_start = points.back();
  out.push_back(last_start + reach * directions.back());
  return out;
}

}  // namespace

std::vector<std::pair<Vec2, Vec2>> joint_traces(const JointSet& set, double block_size, const Vec2& lo,
                                                const Vec2& hi) {
  std::vector<std::pair<Vec2, Vec2>> traces;
  const double spacing = joint_spacing(set, block_size);
  const double reach = (hi - lo).norm();
  if (!(spacing > 0.0)) return traces;
  if (set.parallel_to.size() >= 2) {
    // Curves above the polyline at offset + k spacing, k >= 1, until they leave the box.
    for (int k = 1; k * spacing + set.offset <= reach; ++k) {
      const std::vector<Vec2> curve = offset_polyline(set.parallel_to, set.offset + k * spacing, reach);
      for (size_t q = 0; q + 1 < curve.size(); ++q) traces.emplace_back(curve[q], curve[q + 1]);
    }
    return traces;
  }
  const double dip = set.dip * M_PI / 180.0;
  const Vec2 along(std::cos(dip), -std::sin(dip));  // dipping towards +x
  const Vec2 normal(-along.y(), along.x());
  // Range of n.p over the box corners gives the joints that can cross it.
  double nmin = 1e300, nmax = -1e300;
  for (const Vec2& c : {lo, hi, Vec2(lo.x(), hi.y()), Vec2(hi.x(), lo.y())}) {
    nmin = std::min(nmin, normal.dot(c));
    nmax = std::max(nmax, normal.dot(c));
  }
  const Vec2 centre = 0.5 * (lo + hi);
  const long first = static_cast<long>(std::ceil((nmin - set.offset) / spacing));
  const long last = static_cast<long>(std::floor((nmax - set.offset) / spacing));
  for (long k = first; k <= last; ++k) {
    const double level = set.offset + k * spacing;
    const Vec2 foot = centre + (level - normal.dot(centre)) * normal;
    traces.emplace_back(foot - reach * along, foot + reach * along);
  }
  return traces;
}

}  // namespace ddafit
