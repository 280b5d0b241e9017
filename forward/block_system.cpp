#include "forward/block_system.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <span>

#include "forward/geometry.hpp"

namespace ddafit {

void refresh_block_geometry(BlockSystem& system, int b) {
  Block& block = system.blocks[b];
  const std::vector<Vec2> polygon(system.vertices.begin() + block.first_vertex,
                                  system.vertices.begin() + block.first_vertex + block.vertex_count);
  const PolygonMoments m = polygon_moments(polygon);
  block.area = m.area;
  block.centroid = m.centroid;
  block.s_xx = m.s_xx;
  block.s_yy = m.s_yy;
  block.s_xy = m.s_xy;
}

double longest_elastic_period(const Scene& scene, const BlockSystem& system, int* which) {
  double longest = 0.0;
  if (which) *which = -1;
  for (int b = 0; b < static_cast<int>(system.blocks.size()); ++b) {
    const Block& block = system.blocks[b];
    if (block.fixed) continue;
    const Material& m = scene.materials[block.material];
    const double period = std::sqrt(block.area) / std::sqrt(m.young_modulus / m.density);
    if (period > longest) {
      longest = period;
      if (which) *which = b;
    }
  }
  return longest;
}

double block_length_along(const BlockSystem& system, int b, const Vec2& t) {
  const Block& block = system.blocks[b];
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v) {
    const double s = system.vertices[v].dot(t);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return hi - lo;
}

BlockSystem build_block_system(const Scene& scene) {
  BlockSystem s;
  s.interfaces = scene.interfaces;
  s.water = scene.water;
  for (const Material& m : scene.materials) {
    s.elastic.push_back(elastic_matrix(m.young_modulus, m.poisson_ratio, scene.options.plane_strain));
    s.density.push_back(m.density);
  }

  std::map<std::string, int> group_ids;
  for (const BlockInput& in : scene.blocks) {
    const std::string& g = in.group.empty() ? in.name : in.group;
    if (!group_ids.count(g)) {
      group_ids.emplace(g, static_cast<int>(s.group_names.size()));
      s.group_names.push_back(g);
    }
  }
  s.group_count = static_cast<int>(s.group_names.size());
  s.group_interface.assign(s.group_count * s.group_count, scene.default_interface);
  for (const ContactRule& rule : scene.contact_rules) {
    const auto a = group_ids.find(rule.group_a);
    const auto b = group_ids.find(rule.group_b);
    if (a == group_ids.end() || b == group_ids.end()) continue;  // reader rejects these
    s.group_interface[a->second * s.group_count + b->second] = rule.interface;
    s.group_interface[b->second * s.group_count + a->second] = rule.interface;
  }

  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const BlockInput& in : scene.blocks) {
    Block block;
    block.first_vertex = static_cast<int>(s.vertices.size());
    block.vertex_count = static_cast<int>(in.polygon.size());
    block.material = in.material;
    block.group = group_ids.at(in.group.empty() ? in.name : in.group);
    block.fixed = in.fixed;
    if (!in.fixed) block.unknown = s.free_block_count++;
    std::vector<Vec2> polygon = in.polygon;
    if (signed_area(polygon) < 0.0) std::reverse(polygon.begin(), polygon.end());
    for (const Vec2& p : polygon) {
      s.vertices.push_back(p);
      s.vertex_block.push_back(static_cast<int>(s.blocks.size()));
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    s.blocks.push_back(block);
    s.block_names.push_back(in.name);
    const int b = static_cast<int>(s.blocks.size()) - 1;
    refresh_block_geometry(s, b);
    if (!in.fixed) {
      // Rigid-body velocity about the centroid; no initial strain rate.
      s.blocks[b].velocity << in.velocity.x(), in.velocity.y(), in.angular_velocity, 0, 0, 0;
    }
  }
  s.half_model_size = 0.5 * std::max(hi.x() - lo.x(), hi.y() - lo.y());
  for (const Block& b : s.blocks)
    if (!b.fixed)
      s.least_free_width = std::min(
          s.least_free_width, least_width(std::span<const Vec2>(s.vertices).subspan(b.first_vertex, b.vertex_count)));

  for (const MeasurePoint& mp : scene.measure) {
    MaterialPoint point;
    point.position = point.initial_position = mp.at;
    // Prefer a free block: a point on a shared boundary belongs to what moves.
    double best = std::numeric_limits<double>::infinity();
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
      const Block& block = s.blocks[b];
      const std::vector<Vec2> polygon(s.vertices.begin() + block.first_vertex,
                                      s.vertices.begin() + block.first_vertex + block.vertex_count);
      const bool inside = point_in_polygon(mp.at, polygon);
      const double gap = inside ? 0.0 : distance_to_boundary(mp.at, polygon);
      const double rank = gap + (block.fixed ? 1e-12 : 0.0);
      if (rank < best) {
        best = rank;
        point.block = b;
      }
    }
    s.points.push_back(point);
  }
  return s;
}

}  // namespace ddafit
