// Cutting a region into blocks with an exact 2D arrangement (CGAL): the region outline
// and every joint trace go in as segments, the bounded faces inside the region come out
// as blocks. Exact constructions make the tiling exact whatever the joint angles; slivers
// are then merged into a neighbour by removing the edge they share.
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <cmath>
#include <optional>
#include <unordered_set>

#include "forward/geometry.hpp"
#include "forward/mesh/arrangement_size.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Traits = CGAL::Arr_segment_traits_2<Kernel>;
using Point = Kernel::Point_2;
using Segment = Traits::Curve_2;
// Face data: 1 for a face inside the region (a block), 0 outside.
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;

// A merged block may not exceed this multiple of block_size^2.
constexpr double kMaxMergedAreaRatio = 4.0;

// More blocks than this from one region is a spacing mistake, not a model.
constexpr double kMaxBlocksPerRegion = 2.0e5;

Vec2 to_vec(const Point& p) { return Vec2(CGAL::to_double(p.x()), CGAL::to_double(p.y())); }

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

std::vector<Vec2> face_polygon(Arrangement::Face_const_handle f) {
  std::vector<Vec2> poly;
  auto he = f->outer_ccb();
  const auto start = he;
  do {
    poly.push_back(to_vec(he->source()->point()));
  } while (++he != start);
  return poly;
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

// Interior angle of the corner at p between its neighbours (degrees; > 180 for a
// reflex corner of a counter-clockwise polygon).
double corner_angle(const Vec2& previous, const Vec2& p, const Vec2& next) {
  const Vec2 a = (previous - p).normalized(), b = (next - p).normalized();
  const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
  return cross(previous, p, next) < 0.0 ? 360.0 - angle : angle;
}

bool is_region_corner(const Vec2& p, const std::vector<Vec2>& region_corners) {
  return std::any_of(region_corners.begin(), region_corners.end(),
                     [&](const Vec2& c) { return (c - p).squaredNorm() < 1e-18; });
}

// The smallest corner angle, region corners excepted (merging cannot change those).
double smallest_angle(const std::vector<Vec2>& poly, const std::vector<Vec2>& region_corners) {
  double smallest = 180.0;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k)
    if (!is_region_corner(poly[k], region_corners))
      smallest = std::min(smallest, corner_angle(poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]));
  return smallest;
}

// The sharpest corner below min_angle (region corners excepted), or NaN when none is.
Vec2 sharpest_corner(const std::vector<Vec2>& poly, const std::vector<Vec2>& region_corners, double min_angle) {
  Vec2 sharpest = Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
  double smallest = min_angle;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k) {
    if (is_region_corner(poly[k], region_corners)) continue;
    const double angle = corner_angle(poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]);
    if (angle < smallest) {
      smallest = angle;
      sharpest = poly[k];
    }
  }
  return sharpest;
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

// Removes vertex v if it now joins two collinear edges, so blocks carry no vertex that
// only a deleted joint needed.
void merge_if_collinear(Arrangement& arr, Arrangement::Vertex_handle v) {
  if (v->degree() != 2) return;
  auto e1 = v->incident_halfedges();
  auto e2 = std::next(e1);
  const Point p = e1->source()->point(), q = e2->source()->point();
  if (!CGAL::collinear(p, v->point(), q)) return;
  arr.merge_edge(e1, e2->twin(), Segment(p, q));
}

// Vertices on the outer boundaries of both faces. Merging across one edge keeps a
// simple block only when the faces share just that edge's two end points; more means a
// second contact that would pinch the merged block or wrap it round a hole.
int shared_vertices(Arrangement::Face_const_handle f, Arrangement::Face_const_handle g) {
  std::vector<Arrangement::Vertex_const_handle> mine;
  auto he = f->outer_ccb();
  const auto start = he;
  do mine.push_back(he->source());
  while (++he != start);
  int shared = 0;
  auto other = g->outer_ccb();
  const auto other_start = other;
  do shared += std::count(mine.begin(), mine.end(), other->source()) > 0;
  while (++other != other_start);
  return shared;
}

// Whether f can merge with its neighbour g: the edges they share must form one
// contiguous chain, and they may touch nowhere else (else the merged block would pinch
// or wrap round a hole). The chain's other edges are left dangling by the merge and
// removed by remove_dangling_edges().
bool mergeable(Arrangement::Face_const_handle f, Arrangement::Face_const_handle g) {
  std::vector<bool> shared;
  auto he = f->outer_ccb();
  const auto start = he;
  do shared.push_back(he->twin()->face() == g);
  while (++he != start);
  int runs = 0, edges = 0;
  for (size_t k = 0; k < shared.size(); ++k) {
    edges += shared[k];
    runs += shared[k] && !shared[(k + shared.size() - 1) % shared.size()];
  }
  return runs == 1 && shared_vertices(f, g) == edges + 1;
}

// The shortest edge a face shares with another face of the region (edges on the
// region's outline cannot be merged away).
double shortest_inside_edge(Arrangement::Face_const_handle f) {
  double shortest = 1e300;
  auto he = f->outer_ccb();
  const auto start = he;
  do {
    if (!he->twin()->face()->is_unbounded() && he->twin()->face()->data() == 1)
      shortest = std::min(shortest, (to_vec(he->target()->point()) - to_vec(he->source()->point())).norm());
  } while (++he != start);
  return shortest;
}

// A sliver that shared two edges with its neighbour leaves, once merged across one,
// the other edge with the same face on both sides: a spike into the block. Remove such
// edges (and the vertices they leave alone), then the vertices left joining two collinear
// edges, until none is left. Each pass walks the edges once: restarting from the first
// edge after every removal made this quadratic (seconds for a surface with a tall spike).
void remove_dangling_edges(Arrangement& arr) {
  for (bool again = true; again;) {
    again = false;
    // Ends are kept during the pass (no handle goes stale) and tidied after it.
    std::vector<Arrangement::Vertex_handle> ends;
    for (auto e = arr.edges_begin(); e != arr.edges_end();) {
      auto next = std::next(e);
      if (e->face() == e->twin()->face() && e->face()->data() == 1) {
        ends.push_back(e->source());
        ends.push_back(e->target());
        arr.remove_edge(e, false, false);
        again = true;
      }
      e = next;
    }
    const auto address = [](Arrangement::Vertex_handle v) { return &*v; };
    std::sort(ends.begin(), ends.end(), [&](auto a, auto b) { return address(a) < address(b); });
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    for (auto v : ends) {
      if (v->is_isolated())
        arr.remove_isolated_vertex(v);
      else
        merge_if_collinear(arr, v);
    }
  }
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
    const double spacing = set.spacing > 0.0 ? set.spacing : set.spacing_ratio * block_size;
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
    family.spacing = set.spacing > 0.0 ? set.spacing : set.spacing_ratio * block_size;
    for (const auto& [a, b] : joint_traces(set, block_size, lo, hi))
      if (auto piece = clip(a, b, lo, hi)) family.pieces.push_back(*piece);
  }
  const double edges = estimated_arrangement_edges(families, settings.max_arrangement_edges);
  stats.estimated_edges += edges;
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

  // Merge slivers into the inside neighbour across their longest shared edge, round by
  // round until none is left (a merge can leave a new, larger sliver next door).
  const double min_area = settings.min_area_ratio * block_size * block_size;
  const double min_edge = settings.min_edge_ratio * block_size;
  for (int round = 0; round < 50; ++round) {
    std::vector<Arrangement::Halfedge_handle> to_remove;
    // Faces merged this round (a face merges once per round; its shape has changed).
    std::unordered_set<const void*> touched;
    const auto is_touched = [&](Arrangement::Face_const_handle g) { return touched.count(&*g) > 0; };
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      if (f->is_unbounded() || f->data() != 1) continue;
      if (is_touched(f)) continue;
      const std::vector<Vec2> poly = face_polygon(f);
      const bool short_edged = shortest_inside_edge(f) < min_edge;
      if (!short_edged && signed_area(poly) >= min_area && smallest_angle(poly, outline) >= settings.min_angle)
        continue;
      // The neighbour: across an edge of at least a quarter of the sliver's longest
      // edge (so the merge removes the thin direction), the smallest such neighbour (so
      // merges do not snowball into one giant block), within the size cap.
      const double own_area = signed_area(poly);
      double longest = 0.0;
      auto he = f->outer_ccb();
      const auto start = he;
      do longest = std::max(longest, (to_vec(he->target()->point()) - to_vec(he->source()->point())).norm());
      while (++he != start);
      // Second tier, when no neighbour passes: any edge, four times the size cap; third,
      // no cap at all, since a sliver left alone is worse than a large block. Going
      // uncapped at once made merges snowball when many blocks count as slivers.
      // A sharp corner is removed by merging across one of the two edges that form it;
      // any other merge keeps the corner, and the grown block is a sliver again (a joint
      // running at 1 degree to the ground surface snowballed into a 93-corner block).
      // Those two edges are tried first, through all three tiers.
      const Vec2 corner = sharpest_corner(poly, outline, settings.min_angle);
      const bool sharp = corner.allFinite();
      Arrangement::Halfedge_handle best;
      double best_area = 1e300;
      for (int stage = sharp ? 0 : 3; stage < 6 && best_area == 1e300; ++stage) {
        const int tier = stage % 3;
        const bool at_corner = stage < 3;
        do {
          auto other = he->twin()->face();
          const double length = (to_vec(he->target()->point()) - to_vec(he->source()->point())).norm();
          if (other->is_unbounded() || other->data() != 1 || other == f) continue;
          if (at_corner && (to_vec(he->source()->point()) - corner).squaredNorm() > 1e-18 &&
              (to_vec(he->target()->point()) - corner).squaredNorm() > 1e-18)
            continue;
          // A block that is only short-edged merges across its short edge, which removes it.
          if (short_edged && length >= min_edge) continue;
          if (!short_edged && !at_corner && tier == 0 && length < 0.25 * longest) continue;
          if (is_touched(other)) continue;
          const double other_area = signed_area(face_polygon(other));
          const double cap = tier == 2 ? 1e300 : (tier == 0 ? 1.0 : 4.0) * kMaxMergedAreaRatio * block_size * block_size;
          if (own_area + other_area > cap) continue;
          if (other_area < best_area && mergeable(f, other)) {
            best_area = other_area;
            best = he;
          }
        } while (++he != start);
      }
      if (best_area == 1e300) continue;
      touched.insert(&*f);
      touched.insert(&*best->twin()->face());
      to_remove.push_back(best);
    }
    if (to_remove.empty()) break;
    for (auto he : to_remove) {
      auto source = he->source(), target = he->target();
      arr.remove_edge(he, false, false);
      merge_if_collinear(arr, source);
      merge_if_collinear(arr, target);
      ++stats.merged_slivers;
    }
    remove_dangling_edges(arr);
  }

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
    const double angle = smallest_angle(poly, outline);
    stats.smallest_angle = std::min(stats.smallest_angle, angle);
    if (area < min_area || angle < settings.min_angle || shortest_inside_edge(f) < min_edge) ++stats.remaining_slivers;
    blocks.push_back(std::move(poly));
  }
  stats.block_count += static_cast<int>(blocks.size());
  stats.area_error = std::max(stats.area_error, std::abs(total - region_area) / region_area);
  return blocks;
}

}  // namespace ddafit
