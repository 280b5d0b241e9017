// Cutting a region into blocks with an exact 2D arrangement (CGAL): the region outline
// and every joint trace go in as segments, the bounded faces inside the region come out
// as blocks. Exact constructions make the tiling exact whatever the joint angles; slivers
// are then merged into a neighbour by removing the edge they share.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "forward/geometry.hpp"
#include "forward/mesh/arrangement.hpp"
#include "forward/mesh/arrangement_size.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit {
namespace {

using cut::Arrangement;
using cut::face_polygon;
using cut::Point;
using cut::Segment;

// More blocks than this from one region is a spacing mistake, not a model.
constexpr double kMaxBlocksPerRegion = 2.0e5;

// Liang-Barsky clip of segment a-b to the box [lo, hi].
std::optional<std::pair<Vec2, Vec2>> clip(const Vec2& a, const Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {a.x() - lo.x(), hi.x() - a.x(), a.y() - lo.y(), hi.y() - a.y()};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return std::nullopt;
    } else {
      const double t = q[k] / p[k];
      if (p[k] < 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
    }
  }
  if (t0 >= t1) return std::nullopt;
  return std::make_pair(a + t0 * d, a + t1 * d);
}

// A point strictly inside a simple polygon: the centroid if it is inside, else the
// centroid of the first ear-like triple of vertices that is.
Vec2 interior_point(const std::vector<Vec2>& poly) {
  const PolygonMoments m = polygon_moments(poly);
  if (point_in_polygon(m.centroid, poly)) return m.centroid;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k) {
    const Vec2 c = (poly[k] + poly[(k + 1) % n] + poly[(k + 2) % n]) / 3.0;
    if (point_in_polygon(c, poly)) return c;
  }
  return m.centroid;
}

// Distinct exact points can round to doubles a few ulps apart (three joints nearly
// concurrent): drop a vertex that close to the previous one.
std::vector<Vec2> without_near_repeats(const std::vector<Vec2>& poly, double eps) {
  std::vector<Vec2> out;
  for (const Vec2& p : poly)
    if (out.empty() || (p - out.back()).norm() > eps) out.push_back(p);
  while (out.size() > 3 && (out.front() - out.back()).norm() <= eps) out.pop_back();
  return out;
}

}  // namespace

std::vector<std::vector<Vec2>> cut_region(const RegionInput& region, const MeshSettings& settings,
                                          MeshStats& stats, std::string& problem) {
  std::vector<Vec2> outline = region.polygon;
  if (signed_area(outline) < 0.0) std::reverse(outline.begin(), outline.end());
  const double region_area = signed_area(outline);
  const double block_size = region.block_size > 0.0 ? region.block_size : settings.block_size;
  Vec2 lo = outline[0], hi = outline[0];
  for (const Vec2& p : outline) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec2 margin = 0.01 * (hi - lo) + Vec2::Constant(1e-6);
  lo -= margin;
  hi += margin;

  std::vector<Segment> segments;
  for (size_t k = 0; k < outline.size(); ++k) {
    const Vec2& a = outline[k];
    const Vec2& b = outline[(k + 1) % outline.size()];
    segments.emplace_back(Point(a.x(), a.y()), Point(b.x(), b.y()));
  }
  double densest = 0.0;  // joints per metre, summed over sets, for the size guard
  for (const JointSet& set : region.joint_sets) {
    const double spacing = joint_spacing(set, block_size);
    densest += 1.0 / spacing;
  }
  if (densest * densest * region_area > kMaxBlocksPerRegion) {
    const double blocks = densest * densest * region_area;
    char count[48];
    if (blocks < 1e15)
      std::snprintf(count, sizeof count, "about %.2g", blocks);
    else
      std::snprintf(count, sizeof count, "more than 1e15");  // an infinite count says no more
    problem = std::string("joint spacings would cut the region into ") + count + " blocks (at most " +
              std::to_string(static_cast<long>(kMaxBlocksPerRegion)) + "); raise the spacings or block_size";
    return {};
  }
  // The work bound (arrangement_size.hpp): first the pieces the sets would lay, then the
  // edges their crossings would make.
  const auto refuse = [&](const char* what, double amount) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "cutting would %s %.2g (mesh.max_arrangement_edges = %.3g): joint traces span the region's "
                  "bounding box, %.0f x %.0f m, which is large for the region's %.3g m2; look for a stray outline "
                  "or surface point, or raise block_size or mesh.max_arrangement_edges",
                  what, amount, settings.max_arrangement_edges, hi.x() - lo.x(), hi.y() - lo.y(), region_area);
    problem = text;
  };
  double planned = static_cast<double>(outline.size());
  for (const JointSet& set : region.joint_sets) planned += planned_trace_pieces(set, block_size, lo, hi);
  if (planned > settings.max_arrangement_edges) {
    refuse("lay joint-trace pieces, about", planned);
    return {};
  }
  std::vector<TraceFamily> families(1);
  for (size_t k = 0; k < outline.size(); ++k) families[0].pieces.emplace_back(outline[k], outline[(k + 1) % outline.size()]);
  for (const JointSet& set : region.joint_sets) {
    TraceFamily& family = families.emplace_back();
    family.straight = set.parallel_to.size() < 2;
    family.along = Vec2(std::cos(set.dip * M_PI / 180.0), -std::sin(set.dip * M_PI / 180.0));
    family.spacing = joint_spacing(set, block_size);
    for (const auto& [a, b] : joint_traces(set, block_size, lo, hi))
      if (auto piece = clip(a, b, lo, hi)) family.pieces.push_back(*piece);
  }
  const double edges = estimated_arrangement_edges(families, settings.max_arrangement_edges);
  stats.estimated_edges += edges;
  if (std::isinf(edges)) {
    refuse("overlap curved joint-trace pieces (parallel_to copies, outline) in more pairs than can be counted, over",
           kCountTestsPerEdge * settings.max_arrangement_edges);
    return {};
  }
  if (edges >= settings.max_arrangement_edges) {
    refuse("build an arrangement of edges, at least", edges);
    return {};
  }
  for (size_t f = 1; f < families.size(); ++f)
    for (const auto& [a, b] : families[f].pieces) segments.emplace_back(Point(a.x(), a.y()), Point(b.x(), b.y()));

  Arrangement arr;
  CGAL::insert(arr, segments.begin(), segments.end());
  stats.arrangement_edges += static_cast<double>(arr.number_of_edges());

  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    f->set_data(0);
    if (f->is_unbounded()) continue;
    if (point_in_polygon(interior_point(face_polygon(f)), outline)) f->set_data(1);
  }

  // Merge slivers into the inside neighbour, round by round (merge_slivers.cpp).
  stats.merged_slivers += cut::merge_slivers(arr, outline, block_size, settings);
  const double min_area = settings.min_area_ratio * block_size * block_size;
  const double min_edge = settings.min_edge_ratio * block_size;

  std::vector<std::vector<Vec2>> blocks;
  double total = 0.0;
  stats.remaining_slivers = 0;
  stats.smallest_area = 1e300;
  stats.smallest_angle = 180.0;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded() || f->data() != 1) continue;
    std::vector<Vec2> poly = without_near_repeats(face_polygon(f), 1e-9 * block_size);
    const double area = signed_area(poly);
    total += area;
    stats.smallest_area = std::min(stats.smallest_area, area);
    const double angle = cut::smallest_angle(poly, outline);
    stats.smallest_angle = std::min(stats.smallest_angle, angle);
    if (area < min_area || angle < settings.min_angle || cut::shortest_inside_edge(f) < min_edge) ++stats.remaining_slivers;
    blocks.push_back(std::move(poly));
  }
  stats.block_count += static_cast<int>(blocks.size());
  stats.area_error = std::max(stats.area_error, std::abs(total - region_area) / region_area);
  return blocks;
}

}  // namespace ddafit
