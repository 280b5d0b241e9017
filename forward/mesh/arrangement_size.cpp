// How big the arrangement that cuts a region will be, estimated before CGAL builds it.
// The cut's cost grows with the arrangement's edges (segments plus twice their crossings),
// and the traces span the region's bounding box, not the region: a ground surface with one
// stray point kilometres high makes a box hundreds of times the region, with as many
// crossings. The estimate lets cut_region refuse such input with a message instead of
// running for minutes (or, with a needle-shaped region, for ever).
#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/mesh/arrangement_size.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Whether the segments cross at a point inside both (touching ends does not count: the
// consecutive pieces of one polyline touch without adding an edge).
bool properly_cross(const Segment2& s, const Segment2& t) {
  const Vec2 d = s.second - s.first, e = t.second - t.first;
  const double a = cross2(d, t.first - s.first), b = cross2(d, t.second - s.first);
  const double c = cross2(e, s.first - t.first), f = cross2(e, s.second - t.first);
  return ((a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0)) && ((c > 0.0 && f < 0.0) || (c < 0.0 && f > 0.0));
}

// Crossings among curved pieces, counted by a sweep over x (pairs whose x-ranges overlap
// are tested); stops counting once `enough` is reached. Returns infinity when more than
// `max_tests` pairs overlap: parallel copies that span the box never cross, yet every pair
// of them would be tested (a thin region along a straight parallel_to line, 1e5 copies,
// is 5e9 tests), so the counting itself needs a bound.
double count_curved_crossings(std::vector<Segment2> pieces, double enough, double max_tests) {
  for (Segment2& p : pieces)
    if (p.second.x() < p.first.x()) std::swap(p.first, p.second);
  std::sort(pieces.begin(), pieces.end(), [](const Segment2& a, const Segment2& b) { return a.first.x() < b.first.x(); });
  double count = 0.0, tests = 0.0;
  for (size_t i = 0; i < pieces.size() && count < enough; ++i)
    for (size_t j = i + 1; j < pieces.size() && pieces[j].first.x() <= pieces[i].second.x(); ++j) {
      if (++tests > max_tests) return std::numeric_limits<double>::infinity();
      if (properly_cross(pieces[i], pieces[j]) && ++count >= enough) break;
    }
  return count;
}

}  // namespace

double planned_trace_pieces(const JointSet& set, double block_size, const Vec2& lo, const Vec2& hi) {
  const double spacing = joint_spacing(set, block_size);
  if (!(spacing > 0.0)) return 0.0;
  const double reach = (hi - lo).norm();
  const double lines = reach / spacing + 2.0;
  // An offset copy has one piece per polyline segment, two at a bevelled corner, and the
  // two run-on ends.
  return set.parallel_to.size() >= 2 ? lines * (2.0 * static_cast<double>(set.parallel_to.size()) + 1.0) : lines;
}

double estimated_arrangement_edges(const std::vector<TraceFamily>& families, double enough) {
  double pieces = 0.0, crossings = 0.0;
  std::vector<Segment2> curved;
  for (const TraceFamily& f : families) {
    pieces += static_cast<double>(f.pieces.size());
    if (!f.straight) curved.insert(curved.end(), f.pieces.begin(), f.pieces.end());
  }
  // A piece of length l at angle theta to a set of parallel lines spaced s crosses at most
  // l |sin theta| / s + 1 of them, and no more than the set has.
  for (size_t j = 0; j < families.size(); ++j) {
    const TraceFamily& lines = families[j];
    if (!lines.straight) continue;
    for (size_t i = 0; i < families.size(); ++i) {
      if (i == j || (families[i].straight && i > j)) continue;  // a straight pair once
      for (const Segment2& p : families[i].pieces) {
        const double across = std::abs(cross2(p.second - p.first, lines.along)) / lines.spacing + 1.0;
        crossings += std::min(across, static_cast<double>(lines.pieces.size()));
      }
    }
  }
  if (pieces + 2.0 * crossings < enough)
    crossings += count_curved_crossings(std::move(curved), enough, kCountTestsPerEdge * enough);
  return pieces + 2.0 * crossings;
}

}  // namespace ddafit
