#include "forward/common/containment_check.hpp"

#include <Eigen/Geometry>
#include <span>
#include <sstream>
#include <vector>

#include "forward/geometry.hpp"

namespace ddafit {
namespace {

std::span<const Vec2> outline(const BlockSystem& s, int b) {
  const Block& block = s.blocks[static_cast<size_t>(b)];
  return {s.vertices.data() + block.first_vertex, static_cast<size_t>(block.vertex_count)};
}

}  // namespace

std::string check_containment(const BlockSystem& s) {
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
  }
  return {};
}

}  // namespace ddafit
