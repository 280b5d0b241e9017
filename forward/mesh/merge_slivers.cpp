// Merging slivers: blocks too small, too sharp or too short-edged to simulate well are
// joined to a neighbour by deleting an edge they share (docs/theory.md, "Slivers").
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "forward/geometry.hpp"
#include "forward/mesh/arrangement.hpp"

namespace ddafit::cut {
namespace {

// A merged block may not exceed this multiple of block_size^2.
constexpr double kMaxMergedAreaRatio = 4.0;

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

}  // namespace

double smallest_angle(const std::vector<Vec2>& poly, const std::vector<Vec2>& region_corners) {
  double smallest = 180.0;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k)
    if (!is_region_corner(poly[k], region_corners))
      smallest = std::min(smallest, corner_angle(poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]));
  return smallest;
}

namespace {

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

}  // namespace

// Edges on the region's outline cannot be merged away, so they do not count.
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

namespace {

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

std::vector<Vec2> face_polygon(Arrangement::Face_const_handle f) {
  std::vector<Vec2> poly;
  auto he = f->outer_ccb();
  const auto start = he;
  do {
    poly.push_back(to_vec(he->source()->point()));
  } while (++he != start);
  return poly;
}

int merge_slivers(Arrangement& arr, const std::vector<Vec2>& outline, double block_size, const MeshSettings& settings) {
  // Merge slivers into the inside neighbour across their longest shared edge, round by
  // round until none is left (a merge can leave a new, larger sliver next door).
  int merges = 0;
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
      ++merges;
    }
    remove_dangling_edges(arr);
  }

  return merges;
}

}  // namespace ddafit::cut
