#include "forward/mirror.hpp"

#include <algorithm>

namespace ddafit {

Scene mirrored_scene(const Scene& scene) {
  Scene m = scene;
  for (BlockInput& b : m.blocks) {
    for (Vec2& v : b.polygon) v.x() = -v.x();
    std::reverse(b.polygon.begin(), b.polygon.end());  // a reflection turns the winding round
    b.velocity.x() = -b.velocity.x();
    b.angular_velocity = -b.angular_velocity;
  }
  m.regions.clear();
  m.explicit_block_count = -1;
  for (MeasurePoint& p : m.measure) p.at.x() = -p.at.x();
  m.gravity.x() = -m.gravity.x();
  for (Vec2& p : m.water.table) p.x() = -p.x();
  std::reverse(m.water.table.begin(), m.water.table.end());  // x increasing again
  for (Vec2& a : m.earthquake.acceleration) a.x() = -a.x();
  return m;
}

void unmirror_history(std::vector<HistoryRow>& history) {
  for (HistoryRow& row : history) {
    row.position.x() = -row.position.x();
    row.displacement.x() = -row.displacement.x();
    row.velocity.x() = -row.velocity.x();
  }
}

}  // namespace ddafit
