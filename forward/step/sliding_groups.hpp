// The sliding groups of the settling before t = 0 (settle_sliding.hpp): the settled free blocks
// joined by their loaded points that do not slide, the direction each slides in, and the net
// force along it. Shared by settle_sliding.cpp and held_groups.cpp.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/kinematics.hpp"

namespace ddafit {

// A point carries load when its normal force is above this share of the largest one: points
// at rest beside each other (the flush sides of a row of cubes) have no normal force, and
// their "sliding" is no slide of a block.
inline constexpr double kLoadedShare = 1e-6;

// Two faces are parallel when the sine of the angle between them is under this (0.06 deg).
inline constexpr double kParallelSine = 1e-3;

// Whether unit directions a and b lie along one line (kParallelSine).
inline bool parallel(const Vec2& a, const Vec2& b) { return std::abs(cross2(a, b)) <= kParallelSine; }

struct SlidingGroups {
  std::vector<int> group;       // per block: its group, -1 if not settled or fixed
  std::vector<Vec2> tangent;    // per group: the direction it slides in along its face, zero if none
  std::vector<char> on_ground;  // per group: its tangent is its slip against blocks outside the settled ones
  bool resolved = true;         // false: a group slides on faces that are not parallel
  bool any = false;             // a group slides
};

// The direction along m.tangent in which block `b` (of the manifold) moves against the other.
inline double side(const ContactManifold& m, int b) { return b == m.block_b ? 1.0 : -1.0; }

// The largest normal force of any point: kLoadedShare is a share of it.
double largest_normal_force(const ContactSet& contacts);

// The settled free blocks joined by loaded points that do not slide, and the direction each group
// slides in. Blocks joined by a sliding point slip against each other (a block on a weaker joint of
// the block beneath it), each group at its own acceleration; where the joint is as strong as the
// face below, both accelerations come out equal (add_inertial_loads), as one group's would. A group
// with a block in `held` does not slide.
SlidingGroups sliding_groups(const BlockSystem& s, const ContactSet& contacts, const std::vector<char>& settled,
                             const std::vector<char>& held);

// Per group, t . sum F_i: the net force along its slip of the blocks of each sliding group (zero
// for the others). F's translation rows hold each block's net force at D = 0 (gravity, the
// springs' present forces and the sliding points' friction; assemble.hpp, with the blocks'
// velocities zero); the forces between blocks of the group cancel in the sum.
std::vector<double> net_force_along(const BlockSystem& s, const SlidingGroups& g, const Eigen::VectorXd& f);

}  // namespace ddafit
