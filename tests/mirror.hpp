// A scene's mirror image (x -> -x), for tests that check a class of events both ways round.
// The physics is the same; what changes is the order in which the blocks, their pieces and
// their contacts meet the motion (the broad phase sorts along x, each polygon's corners are
// numbered the other way round), which a Gauss-Seidel sweep, the open-close iteration and the
// narrow phase's tie-breaks are not blind to (docs/theory.md §13, "Limits of the substep
// solver"). A class passed one way round only is an instance.
#pragma once

#include <algorithm>

#include "forward/simulation.hpp"

namespace ddafit {

// Every polygon, velocity, spin, measure point and the gravity reflected in the vertical axis;
// each polygon turned back counter-clockwise.
[[maybe_unused]] inline void mirror_scene(Scene& s) {
  for (BlockInput& b : s.blocks) {
    for (Vec2& v : b.polygon) v.x() = -v.x();
    std::reverse(b.polygon.begin(), b.polygon.end());
    b.velocity.x() = -b.velocity.x();
    b.angular_velocity = -b.angular_velocity;
  }
  for (MeasurePoint& m : s.measure) m.at.x() = -m.at.x();
  s.gravity.x() = -s.gravity.x();
}

// A mirrored run's history reflected back, so that it reads as the unmirrored scene's.
[[maybe_unused]] inline void mirror_history(SimulationResult& r) {
  for (HistoryRow& row : r.history) {
    row.position.x() = -row.position.x();
    row.displacement.x() = -row.displacement.x();
    row.velocity.x() = -row.velocity.x();
  }
}

}  // namespace ddafit
