// Legacy VTK polydata files of the blocks, for ParaView (a numbered series opens as an
// animation).
#pragma once

#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/scene.hpp"

namespace ddafit::app {

// From a scene's input polygons (mesh output).
void write_scene_vtk(const std::string& path, const Scene& scene);

// From the running state (snapshots): cell data block id, fixed, speed of the centroid.
void write_state_vtk(const std::string& path, const BlockSystem& system, double time);

}  // namespace ddafit::app
