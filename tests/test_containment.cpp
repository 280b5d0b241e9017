// The check that stops a run when a free block has passed into a fixed one
// (forward/common/containment_check.hpp): the failure neither the energy audit nor the
// overlap check can see, since the lost block has no contact left.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/common/containment_check.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

using verification::block;

// A 10 m x 4 m fixed base and a free block resting on it, far from the origin as on Vajont.
BlockSystem base_and(std::vector<Vec2> free_polygon) {
  Scene scene;
  scene.materials.push_back({"rock", 2700.0, 5.0e9, 0.25});
  const Vec2 o(1500.0, 600.0);
  scene.blocks.push_back(block("bank", {o, o + Vec2(10, 0), o + Vec2(10, 4), o + Vec2(0, 4)}, true));
  for (Vec2& v : free_polygon) v += o;
  scene.blocks.push_back(block("toe", free_polygon, false));
  return build_block_system(scene);
}

void move_block(BlockSystem& s, int b, const Vec2& by) {
  Block& block = s.blocks[b];
  for (int k = 0; k < block.vertex_count; ++k) s.vertices[block.first_vertex + k] += by;
  block.centroid += by;
}

const std::vector<Vec2> kSquare = {{4, 4}, {5, 4}, {5, 5}, {4, 5}};

TEST(Containment, ABlockOnTheBaseIsNotContained) {
  const BlockSystem s = base_and(kSquare);
  EXPECT_EQ(check_containment(s), "");
}

TEST(Containment, ABlockHalfWayIntoTheBaseIsNamed) {
  // Sunk 0.6 m: its centroid 0.1 m inside the base. Any depth past the centroid is a
  // block no contact holds; the message names the block, the fixed block and the remedy.
  BlockSystem s = base_and(kSquare);
  move_block(s, 1, Vec2(0.0, -0.6));
  const std::string problem = check_containment(s);
  EXPECT_NE(problem.find("'toe'"), std::string::npos) << problem;
  EXPECT_NE(problem.find("'bank'"), std::string::npos) << problem;
  EXPECT_NE(problem.find("time.step"), std::string::npos) << problem;
}

TEST(Containment, AnLWhoseCentroidIsOutsideItselfIsNotJudgedByIt) {
  // A thin L hooked over the base's top right corner: one arm lies on the top, the other
  // hangs down the side, and its centroid, (9.44, 3.44) m from the base's corner, lies
  // outside its own outline and inside the base. A legal configuration, not a lost block.
  const std::vector<Vec2> hook = {{7, 4}, {10, 4}, {10, 1}, {10.5, 1}, {10.5, 4.5}, {7, 4.5}};
  BlockSystem s = base_and(hook);
  EXPECT_EQ(check_containment(s), "");
}

}  // namespace
}  // namespace ddafit
