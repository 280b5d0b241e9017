// Regions cut into blocks by joint sets (Shi's "DC" step). The region and joint-set
// structs are part of the scene (forward/scene.hpp); the cutting is in cut_region.cpp.
#pragma once

#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

struct MeshStats {
  int block_count = 0;
  double mean_block_size = 0.0;  // sqrt(mean area), the seed's measure
  double smallest_area = 0.0;
  double smallest_angle = 0.0;   // deg, over all block corners that are not region corners
  int merged_slivers = 0;
  int remaining_slivers = 0;     // slivers no neighbour could take (reported, not hidden)
  double area_error = 0.0;       // |sum of block areas - region area| / region area
  // The mesher's work (summed over a region's cuts): edges of the arrangement CGAL built,
  // and the estimate mesh.max_arrangement_edges was checked against before building it.
  double arrangement_edges = 0.0;
  double estimated_edges = 0.0;
};

struct RegionMesh {
  std::string region;
  MeshStats stats;
};

// Replaces the generated blocks of `scene` (those after scene.explicit_block_count)
// with the blocks of its regions, cut at scene.mesh.block_size. Returns one entry per
// region, or sets `problem` ("regions[K]: ...") and leaves the scene unchanged.
std::vector<RegionMesh> generate_blocks(Scene& scene, std::string& problem);

// The ranges of the mesh settings (block_size 0 = unset; else in (0, 1e6] m), checked
// before any cutting: by the reader and when a study parameter changes one.
std::vector<SceneError> validate_mesh_settings(const MeshSettings& mesh);

// A set's spacing in m: its own `spacing`, else spacing_ratio x the region's block size.
inline double joint_spacing(const JointSet& set, double block_size) {
  return set.spacing > 0.0 ? set.spacing : set.spacing_ratio * block_size;
}

// The joint traces of one set across a region's bounding box, as segments.
std::vector<std::pair<Vec2, Vec2>> joint_traces(const JointSet& set, double block_size, const Vec2& lo,
                                                const Vec2& hi);

// Cuts one region by its joint sets. Returns the blocks as counter-clockwise polygons
// that tile the region; `problem` is set (and nothing returned) when the input cannot
// be cut (e.g. a spacing so small the region would become millions of blocks).
std::vector<std::vector<Vec2>> cut_region(const RegionInput& region, const MeshSettings& settings,
                                          MeshStats& stats, std::string& problem);

}  // namespace ddafit
