// Stage 2 of a step, both solvers: the narrow phase. One manifold per touching pair of
// convex pieces: one normal (the separating axis of the reference face, or the flush face),
// at most two points, a single point with the normal joining the corners when two corners
// meet (forward/contact/manifold.hpp). Points keep their state from the last step by
// feature id; each manifold is given the slip history of its overriding face.
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/contact/manifold.hpp"

namespace ddafit {

// The flush tolerance eta of manifold.hpp as a fraction of the smaller free block's size
// (the square root of its area). Two polygons along one line within this get the flush
// rules (manifold.hpp); a step higher than this is always a step. Twice the largest overlap the solvers allow (1 % of the
// smaller block: an overlap that deep must not turn a flush joint into a step), and below
// the 5 % of a 5 cm step under a 1 m block, which must stop a block arriving at 2 m/s
// (test_joint_crossing.cpp).
inline constexpr double kFlushRatio = 0.02;
// Of the smaller free block's size (the square root of its area): the least depth of a proud
// edge (manifold.hpp, "Proud edges") when the linear slop is smaller. A row block loaded by a
// 3 m x 1.5 m slider sat 1.6 um deeper than its unloaded neighbour; with the displacement limit
// at 2e-4 the slop was 1.3 um and the slider hooked on a row of 1.0 m x 0.3 m blocks (2.7 um
// here; 2.5e-6 of the size, 1.4 um, did not free it). On Vajont the slop (0.25 mm) is the larger
// for every block under 50 m: sections I and II and section VII's first 10 s are the same to the
// byte with and without this floor (revision 2026-12-01.2).
inline constexpr double kProudRatio = 5e-6;

struct CollideSettings {
  double margin = 0.0;       // m: points are kept while their gap is below this (speculative)
  // m, per block (empty: none): a block moving further in the step than the margin covers
  // (a block in flight) widens the margin of its pairs by this much, so it cannot pass
  // through a neighbour unseen; overlaps deeper than `margin` alone are still not contacts.
  std::span<const double> extra_reach;
  double linear_slop = 0.0;  // m: tolerance of the separating-axis choice
  bool first_step = false;   // bonds (cohesion, tension) form only between blocks touching at t = 0
  double flush_ratio = kFlushRatio;
  // Down: of two free blocks, the upper one overrides (seed Eq. 2: its length sets d_c).
  Vec2 gravity = Vec2(0.0, -9.81);
};

// Replaces `contacts` (the last step's, manifolds sorted by piece pair, histories by key)
// with this step's. The detection's `geometry`, `previous` and `previous_histories` are
// scratch kept between calls (their memory is reused). Returns an empty string, or a
// description of two touching blocks that have no interface.
struct ContactDetection {
  ContactShapes shapes;      // build_shapes(), once per run
  CollideSettings settings;  // first_step is cleared after each detection
  std::vector<Manifold> geometry;  // scratch of the narrow phase
  // Scratch: the last step's manifolds while this step's are built. Kept between calls so
  // that the ~12 MB of section VII's manifolds are not allocated and faulted in every step.
  std::vector<ContactManifold> previous;
  std::vector<SlipHistory> previous_histories;  // the same for assign_histories()
};

// With detection's shapes and settings; its geometry is the narrow phase's scratch.
std::string collide(const BlockSystem& system, ContactDetection& detection,
                    const std::vector<std::pair<int, int>>& pairs, ContactSet& contacts);

}  // namespace ddafit
