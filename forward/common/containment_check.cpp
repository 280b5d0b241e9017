#include "forward/common/containment_check.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "forward/geometry.hpp"

namespace ddafit {
namespace {

std::span<const Vec2> outline(const BlockSystem& s, int b) {
  const Block& block = s.blocks[static_cast<size_t>(b)];
  return {s.vertices.data() + block.first_vertex, static_cast<size_t>(block.vertex_count)};
}

// The distance from p to the nearest edge of the polygon: with p inside, the radius of the
// largest circle about p inside it.
double inradius_about(const Vec2& p, std::span<const Vec2> polygon) {
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2 edge = polygon[(i + 1) % polygon.size()] - a;
    const double length2 = edge.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(edge) / length2, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (a + t * edge - p).norm());
  }
  return nearest;
}

// True when the segment a -> b runs through the polygon's interior: the segment is cut at
// every crossing with an edge and the middle of each piece tested (ends on the boundary,
// or grazing a vertex, are not inside).
bool path_crosses_interior(const Vec2& a, const Vec2& b, std::span<const Vec2> polygon) {
  std::vector<double> cuts{0.0, 1.0};
  const Vec2 r = b - a;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& c = polygon[i];
    const Vec2 e = polygon[(i + 1) % polygon.size()] - c;
    const double denominator = r.x() * e.y() - r.y() * e.x();
    if (denominator == 0.0) continue;  // parallel: an edge along the path adds no crossing
    const Vec2 ac = c - a;
    const double t = (ac.x() * e.y() - ac.y() * e.x()) / denominator;
    const double u = (ac.x() * r.y() - ac.y() * r.x()) / denominator;
    if (t > 0.0 && t < 1.0 && u >= 0.0 && u <= 1.0) cuts.push_back(t);
  }
  if (cuts.size() == 2) return false;
  std::sort(cuts.begin(), cuts.end());
  for (size_t k = 0; k + 1 < cuts.size(); ++k)
    if (point_in_polygon(a + 0.5 * (cuts[k] + cuts[k + 1]) * r, polygon)) return true;
  return false;
}

}  // namespace

void remember_step_start(const BlockSystem& s, StepStart& start) {
  const bool first = start.inradius.size() != s.blocks.size();
  start.centroid.resize(s.blocks.size());
  start.inradius.resize(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    start.centroid[b] = s.blocks[b].centroid;
    if (first) start.inradius[b] = inradius_about(s.blocks[b].centroid, outline(s, static_cast<int>(b)));
  }
}

std::string check_containment(const BlockSystem& s, const StepStart* step_start) {
  // Fixed blocks are few (Vajont: the bedrock and the banks); their boxes reject almost
  // every free block before the polygon test.
  std::vector<int> fixed;
  std::vector<Eigen::AlignedBox2d> boxes;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    if (!s.blocks[b].fixed) continue;
    Eigen::AlignedBox2d box;
    for (const Vec2& v : outline(s, b)) box.extend(v);
    fixed.push_back(b);
    boxes.push_back(box);
  }
  const bool paths = step_start != nullptr && step_start->centroid.size() == s.blocks.size();
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.fixed) continue;
    for (size_t k = 0; k < fixed.size(); ++k) {
      if (!boxes[k].contains(block.centroid) || !point_in_polygon(block.centroid, outline(s, fixed[k]))) continue;
      if (!point_in_polygon(block.centroid, outline(s, b))) break;
      std::ostringstream out;
      out << "block '" << s.block_names[b] << "' has passed into fixed block '" << s.block_names[fixed[k]]
          << "' (its centroid (" << block.centroid.x() << ", " << block.centroid.y()
          << ") m lies inside it): a contact failed to hold it and it would fall through the model. Lower "
             "time.step; with the substep solver, raise time.substeps";
      return out.str();
    }
    if (!paths) continue;
    const Vec2& start = step_start->centroid[static_cast<size_t>(b)];
    const double move = (block.centroid - start).norm();
    if (move == 0.0 || move < 0.25 * step_start->inradius[static_cast<size_t>(b)]) continue;
    if (!point_in_polygon(block.centroid, outline(s, b))) continue;  // a concave block, as above
    Eigen::AlignedBox2d path(start.cwiseMin(block.centroid), start.cwiseMax(block.centroid));
    for (size_t k = 0; k < fixed.size(); ++k) {
      if (!boxes[k].intersects(path) || !path_crosses_interior(start, block.centroid, outline(s, fixed[k]))) continue;
      std::ostringstream out;
      out << "block '" << s.block_names[b] << "' has passed through fixed block '" << s.block_names[fixed[k]]
          << "' (its centroid moved " << move << " m, from (" << start.x() << ", " << start.y()
          << ") to (" << block.centroid.x() << ", " << block.centroid.y()
          << ") m along a line through it): a step carried it past the contact that should have held it. Lower "
             "time.step; with the substep solver, raise time.substeps";
      return out.str();
    }
  }
  return {};
}

}  // namespace ddafit
