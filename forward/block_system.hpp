// The blocks of a running simulation as plain arrays indexed by block id.
// Vertices of all blocks live in one contiguous array, counter-clockwise per block.
#pragma once

#include <string>
#include <algorithm>
#include <limits>
#include <vector>

#include "forward/kinematics.hpp"
#include "forward/scene.hpp"

namespace ddafit {

struct Block {
  int first_vertex = 0;  // into BlockSystem::vertices
  int vertex_count = 0;
  int material = -1;
  int group = -1;
  bool fixed = false;
  int unknown = -1;  // position among the free blocks in the global system; -1 if fixed

  // Geometry, refreshed after every accepted step.
  double area = 0.0;
  Vec2 centroid = Vec2::Zero();
  double s_xx = 0.0, s_yy = 0.0, s_xy = 0.0;  // second moments about the centroid

  Vec6 velocity = Vec6::Zero();  // rates of the six unknowns, carried between steps
  Vec3 stress = Vec3::Zero();    // (sigma_x, sigma_y, tau_xy), Pa
};

// A material point carried by a block (measurement points).
struct MaterialPoint {
  int block = -1;
  Vec2 position = Vec2::Zero();
  Vec2 initial_position = Vec2::Zero();
};

struct BlockSystem {
  std::vector<Block> blocks;
  std::vector<Vec2> vertices;
  std::vector<int> vertex_block;   // owning block of each vertex
  std::vector<Mat3> elastic;       // per material: C of plane strain or stress
  std::vector<double> density;     // per material
  std::vector<Interface> interfaces;
  Water water;  // the pore pressure on the faces (forward/water/hydrostatic.hpp)
  int group_count = 0;
  std::vector<int> group_interface;  // group_count x group_count, -1 = none
  std::vector<std::string> group_names;
  std::vector<std::string> block_names;
  std::vector<MaterialPoint> points;  // in Scene::measure order
  int free_block_count = 0;
  double half_model_size = 0.0;  // half the larger side of the initial bounding box
  // m: the thinnest free block's least width at t = 0 (over its edges, the farthest corner from
  // the edge's line); infinite without free blocks. Caps a step's move (step_move_limit).
  double least_free_width = std::numeric_limits<double>::infinity();

  int next_vertex(int v) const {
    const Block& b = blocks[vertex_block[v]];
    return v + 1 < b.first_vertex + b.vertex_count ? v + 1 : b.first_vertex;
  }
  int previous_vertex(int v) const {
    const Block& b = blocks[vertex_block[v]];
    return v > b.first_vertex ? v - 1 : b.first_vertex + b.vertex_count - 1;
  }
  int interface_between(int block_a, int block_b) const {
    return group_interface[blocks[block_a].group * group_count + blocks[block_b].group];
  }
  double mass(int block) const { return density[blocks[block].material] * blocks[block].area; }
};

// Builds the running state from a validated scene: orients polygons counter-clockwise,
// computes the moments, resolves group interfaces and finds the block of each
// measurement point.
BlockSystem build_block_system(const Scene& scene);

// Recomputes area, centroid and second moments of block b from its vertices.
void refresh_block_geometry(BlockSystem& system, int b);

// Extent of block b measured along unit direction t (the "length of the overriding
// block" that sets the critical distance of seed Eq. 2).
double block_length_along(const BlockSystem& system, int b, const Vec2& t);

// The longest elastic period L / c of the free blocks (L = sqrt(area), c = sqrt(E / rho)): the
// slowest elastic mode of the scene, which a time step resolves first. `which` (if given) is set
// to that block, or -1 when no block is free (the period is then 0).
double longest_elastic_period(const Scene& scene, const BlockSystem& system, int* which = nullptr);

// The largest move a step may give a block, m (model revision 2026-12-06.21): the scene's
// share of half the model (`control.max_displacement_ratio`, Shi's g2) or half the thinnest free
// block's least width, whichever is less. Model-sized alone, a 5 cm block 5 mm thick in a 20 m
// scene could move 1-12 of its own lengths a step, its contacts were met too late, and it ran up
// to 99 % short of seed Eq. 5 on the substep solver, 42 % on the implicit one
// (tests/test_thin_riders.cpp). Half the width
// leaves every Vajont section's 0.25 m a step as it was (the thinnest free block there is 0.54 m
// wide, section X). The contact margin and slop follow the move (collide.hpp).
constexpr double kStepMoveWidthShare = 0.5;
inline double step_move_limit(double max_displacement_ratio, const BlockSystem& s) {
  return std::min(max_displacement_ratio * s.half_model_size, kStepMoveWidthShare * s.least_free_width);
}

}  // namespace ddafit
