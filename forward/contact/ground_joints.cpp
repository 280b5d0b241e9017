#include "forward/contact/ground_joints.hpp"

#include <algorithm>
#include <cmath>


namespace ddafit {
namespace {

// Two fixed blocks' edges lie along one joint when each end of the shorter is within this share
// of the longer edge's length of the longer's line and span: generated blocks share their corners
// to round-off (1e-9 of a coordinate of a few kilometres is a few micrometres).
constexpr double kJointTolerance = 1e-9;
// The fixed blocks that meet at one corner, at most, followed round it.
constexpr int kMostAroundCorner = 16;

struct Edge {
  int from = -1;  // vertex id; the edge runs to system.next_vertex(from)
  Vec2 a, b;
  double lo_x = 0.0, hi_x = 0.0;
};

// Edge f lies along e, facing it, over e's whole length.
bool covers(const Edge& f, const Edge& e) {
  const Vec2 along = f.b - f.a, d = e.b - e.a;
  const double length = along.norm();
  if (!(length > 0.0) || along.dot(d) >= 0.0) return false;
  const double tolerance = kJointTolerance * std::max(length, d.norm()) + 1e-12;
  const Vec2 u = along / length;
  if (std::abs(cross2(u, e.a - f.a)) > tolerance || std::abs(cross2(u, e.b - f.a)) > tolerance) return false;
  const double ta = u.dot(e.a - f.a), tb = u.dot(e.b - f.a);
  return std::min(ta, tb) >= -tolerance && std::max(ta, tb) <= length + tolerance;
}

}  // namespace

GroundJoints find_ground_joints(const BlockSystem& s, double reflex_sine) {
  GroundJoints joints;
  joints.covered.assign(s.vertices.size(), 0);
  joints.reflex.assign(s.vertices.size(), 0);
  joints.shared.assign(s.vertices.size(), 0);
  std::vector<Edge> edges;
  for (const Block& block : s.blocks) {
    if (!block.fixed) continue;
    for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v) {
      const Vec2 a = s.vertices[v], b = s.vertices[s.next_vertex(v)];
      edges.push_back({v, a, b, std::min(a.x(), b.x()), std::max(a.x(), b.x())});
    }
  }
  if (edges.size() < 2) return joints;
  // Sweep along x: only edges whose x-ranges overlap can lie along one another.
  std::sort(edges.begin(), edges.end(), [](const Edge& e, const Edge& f) { return e.lo_x < f.lo_x; });
  std::vector<int> covering(s.vertices.size(), -1);  // per vertex: the edge (index) covering its edge
  for (size_t i = 0; i < edges.size(); ++i) {
    const double reach = edges[i].hi_x + kJointTolerance * (edges[i].hi_x - edges[i].lo_x + 1.0);
    for (size_t j = i + 1; j < edges.size() && edges[j].lo_x <= reach; ++j) {
      const Edge &e = edges[i], &f = edges[j];
      if (s.vertex_block[e.from] == s.vertex_block[f.from]) continue;
      if (covering[e.from] < 0 && covers(f, e)) covering[e.from] = static_cast<int>(j);
      if (covering[f.from] < 0 && covers(e, f)) covering[f.from] = static_cast<int>(i);
    }
  }
  bool any = false;
  for (size_t v = 0; v < covering.size(); ++v) any |= (joints.covered[v] = covering[v] >= 0 ? 1 : 0) != 0;
  if (!any) return joints;

  // The ground's boundary at vertex v, with the covered edges taken out: the direction it
  // arrives in and the one it leaves in. A covered edge hands over to the block that covers it,
  // at that block's corner at v, to its next (or previous) edge there. False when the covering
  // edge runs on past v (a fixed block standing on another's face: its corner keeps its own
  // reading, which the walled rows of tests/test_impact_rebound.cpp are held by) or when the
  // corner is inside the ground all round.
  const auto same_place = [&](const Vec2& p, int v) {
    return (p - s.vertices[v]).norm() <= kJointTolerance * (p.norm() + 1.0);
  };
  const auto leaving = [&](int v, Vec2& direction) {
    for (int round = 0; round < kMostAroundCorner; ++round) {
      if (covering[v] < 0) return direction = s.vertices[s.next_vertex(v)] - s.vertices[v], true;
      const Edge& f = edges[covering[v]];  // runs back along v's edge, towards v
      const int end = s.next_vertex(f.from);
      if (!same_place(s.vertices[end], v)) return false;
      v = end;
    }
    return false;
  };
  const auto arriving = [&](int v, Vec2& direction) {
    for (int round = 0; round < kMostAroundCorner; ++round) {
      const int previous = s.previous_vertex(v);
      if (covering[previous] < 0) return direction = s.vertices[v] - s.vertices[previous], true;
      const Edge& f = edges[covering[previous]];  // runs from v's side back along the edge
      if (!same_place(f.a, v)) return false;
      v = f.from;
    }
    return false;
  };
  for (int v = 0; v < static_cast<int>(s.vertices.size()); ++v) {
    if (!s.blocks[s.vertex_block[v]].fixed) continue;
    if (covering[v] < 0 && covering[s.previous_vertex(v)] < 0) continue;
    Vec2 in, out;
    if (!arriving(v, in) || !leaving(v, out)) continue;
    joints.reflex[v] = turns_inward(in, out, reflex_sine) ? 1 : 0;
    joints.shared[v] = 1;
  }
  return joints;
}

}  // namespace ddafit
