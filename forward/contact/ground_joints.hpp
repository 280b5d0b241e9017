// Joints of the fixed ground (docs/theory.md §3, "Joints of the fixed ground"): where two fixed
// blocks meet along a joint, the joint is inside the ground. Nothing can reach either face of it
// without passing through the other fixed block, so for contact it is what a cut between two
// pieces of one concave block is (manifold.hpp, "Solid edges"), and where the ground's surface
// turns inward at the joint's end (a concave kink, a block standing on another) that corner is a
// reflex corner of the ground (manifold.hpp, "Reflex corners").
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {

// Per vertex of BlockSystem::vertices, for the edge from it to the next vertex of its block:
// covered[v] is 1 when the edge belongs to a fixed block and an edge of another fixed block lies
// along it, facing it, over its whole length (within kJointTolerance of the longer edge's length).
// shared[v] is 1 at a corner where such a joint ends and the blocks on either side of it have
// their corners there; reflex[v] is then 1 when, with the joints taken out, the boundary of the
// fixed blocks turns inward (clockwise, counter-clockwise polygons) at v by more than the sine
// `reflex_sine`.
struct GroundJoints {
  std::vector<char> covered;
  std::vector<char> shared;
  std::vector<char> reflex;
};
GroundJoints find_ground_joints(const BlockSystem& system, double reflex_sine);

// A boundary arriving along `in` and leaving along `out` (counter-clockwise) turns clockwise,
// inward, by more than the sine `sine`: a reflex corner (of a block, or of the fixed ground).
inline bool turns_inward(const Vec2& in, const Vec2& out, double sine) {
  return cross2(in, out) < -sine * in.norm() * out.norm();
}

}  // namespace ddafit
