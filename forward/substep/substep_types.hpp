// Plain data of the substep solver (docs/theory.md, "The substep solver"): the convex
// pieces that contact is detected on, the contact manifolds between pieces of different
// blocks, and each block's effective inverse mass for one substep.
#pragma once

#include <cstdint>
#include <vector>

#include "forward/kinematics.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// A convex piece of a block, for contact only (a concave block is split; its blocks'
// unknowns stay one set of six). Its corners are vertex ids of BlockSystem::vertices,
// counter-clockwise, stored in SubstepShapes::corners[first .. first + count).
struct ConvexPiece {
  int block = -1;
  int first = 0;
  int count = 0;
};

struct SubstepShapes {
  std::vector<ConvexPiece> pieces;
  std::vector<int> corners;
  // Per corner: 1 if the edge to the next corner is part of the block's boundary, 0 if it
  // is a cut between two pieces of the block (manifold.hpp, solid edges).
  std::vector<char> solid;
};

// One contact point of a manifold. The first group survives from step to step (matched
// by id); the second is rebuilt at the start of every step.
struct SubstepPoint {
  std::uint32_t id = 0;  // feature key of the manifold (forward/substep/manifold.hpp)
  int owner = -1;        // vertex id of the corner the point sits on (its block overrides, seed Eq. 2)

  double normal_impulse = 0.0;   // N s/m, accumulated over the last substep (warm start)
  double tangent_impulse = 0.0;  // N s/m
  double slip = 0.0;             // d of seed Eq. 2, m: tangential slip accumulated while touching
  double last_slip = 0.0;        // slip of the last substep, m (mid-substep predictor of d)
  double critical_distance = 0.0;  // d_c, m
  double bond_length = 0.0;        // l_c, m: length cohesion and tension act on
  bool bonded = false;             // cohesion and tension intact (blocks touching at t = 0)

  Vec2 anchor = Vec2::Zero();  // the point at the start of the step, world
  double separation = 0.0;     // at the start of the step, m (< 0: penetration)
  // The point about each block's centroid at the start of the step. The relative
  // velocity is v_rel = (v_b + w_b x r_b) - (v_a + w_a x r_a): the rigid-body rows of
  // T(p) (Shi 1993 eq. 2.2), the strain rows being the blocks' stress (block_stress.hpp).
  Vec2 ra = Vec2::Zero(), rb = Vec2::Zero();
  double normal_mass = 0.0;   // 1 / (J W J^T) along the normal, kg/m
  double tangent_mass = 0.0;  // along the tangent
  double friction = 0.0;      // tan(phi) at the current slip (seed Eq. 2-3)
  double step_normal_impulse = 0.0;   // N s/m, summed over the substeps of this step
  double step_tangent_impulse = 0.0;  // N s/m
  double tension_impulse = 0.0;   // largest tensile impulse per substep while bonded
  double cohesion_impulse = 0.0;  // cohesive shear impulse per substep while bonded
};

struct SubstepManifold {
  int piece_a = -1, piece_b = -1;
  int block_a = -1, block_b = -1;
  int interface = -1;
  Vec2 normal = Vec2::Zero();   // unit, from a to b
  Vec2 tangent = Vec2::Zero();  // normal turned 90 degrees clockwise
  int point_count = 0;
  SubstepPoint points[2];
};

// A block's response to a contact impulse P at r: its velocity changes by P / m and its
// spin by (r x P) / I, with m and I the rigid-body rows of the DDA mass matrix
// (translation and rotation about the centroid; they are diagonal there,
// forward/mass_matrix.hpp). The strain unknowns carry no inertia in the substep solver:
// a block's strain follows from the mean stress its contacts put on it over each step
// (forward/substep/block_stress.hpp). A fixed block has zero inverses.
struct BlockMass {
  double inverse_mass = 0.0;     // 1 / m, m/kg (per metre of thickness)
  double inverse_inertia = 0.0;  // 1 / I about the centroid
  bool moves = false;
};

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Velocity of the material point at r (about the centroid) of a block moving with
// q = (vx, vy, w), the rigid-body part of its six rates; also its displacement for a
// small move q = (dx, dy, dtheta).
inline Vec2 velocity_at(const Vec3& q, const Vec2& r) { return Vec2(q[0] - q[2] * r.y(), q[1] + q[2] * r.x()); }

}  // namespace ddafit
