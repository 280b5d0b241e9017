#include "forward/common/displace_block.hpp"

#include <algorithm>

namespace ddafit {

double block_displacement(const BlockSystem& s, int b, const Vec6& db) {
  const Block& block = s.blocks[b];
  double largest = 0.0;
  for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
    largest = std::max(largest, exact_point_displacement(s.vertices[v], block.centroid, db).norm());
  return largest;
}

void displace_block(BlockSystem& s, int b, const Vec6& db, bool measured) {
  Block& block = s.blocks[b];
  for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
    s.vertices[v] += exact_point_displacement(s.vertices[v], block.centroid, db);
  // Material points move with the same map, before the centroid is refreshed.
  for (MaterialPoint& p : s.points) {
    if (p.block != b) continue;
    const Vec2 shift = exact_point_displacement(p.position, block.centroid, db);
    p.position += shift;
    if (!measured) p.initial_position += shift;
  }
  block.stress += s.elastic[block.material] * db.segment<3>(3);
  refresh_block_geometry(s, b);
}

}  // namespace ddafit
