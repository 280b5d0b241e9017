// Reads back the legacy VTK snapshots `simulate --vtk-interval` writes (vtk_writer.hpp):
// the block polygons of one output time with their speeds, for `ddafit animate`.
#pragma once

#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit::app {

struct Snapshot {
  double time = 0.0;                     // s, from the file's title line
  std::vector<Vec2> points;              // vertices, m
  std::vector<std::vector<int>> polygons;  // per block, indices into points
  std::vector<int> fixed;                // per block, 1 for a fixed block
  std::vector<double> speed;             // per block, centroid speed, m/s
};

// Reads one snapshot. Returns an empty string, or a one-line description of what is wrong
// with the file ("PATH: line N: ...").
std::string read_snapshot(const std::string& path, Snapshot& out);

}  // namespace ddafit::app
