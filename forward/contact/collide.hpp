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
// ... and at most this share of the thinner piece's least width (collide.cpp).
inline constexpr double kFlushWidthShare = 0.5;
// Of the smaller free block's size (the square root of its area): the least depth of a proud
// edge (manifold.hpp, "Proud edges") when the linear slop is smaller. A row block loaded by a
// 3 m x 1.5 m slider sat 1.6 um deeper than its unloaded neighbour; with the displacement limit
// at 2e-4 the slop was 1.3 um and the slider hooked on a row of 1.0 m x 0.3 m blocks (2.7 um
// here; 2.5e-6 of the size, 1.4 um, did not free it). On Vajont the slop (0.25 mm) is the larger
// for every block under 50 m: sections I and II and section VII's first 10 s are the same to the
// byte with and without this floor (revision 2026-12-01.2).
inline constexpr double kProudRatio = 5e-6;
// The substep solver's sag (CollideSettings::sag) in |g| h^2: gravity adds |g| h to a block's
// speed in each substep, and the sweeps and push-out that take it back leave a loaded block up
// to about that times h deeper in its supports than an unloaded neighbour. A 3 m x 1.5 m slider
// from rest on a row of free 0.4 m blocks (15 deg, friction 8 deg) at 10 ms x 4 or x 3 hooked
// on the first joint (a slop of 40 um against a sag of 61-109 um; tests/test_free_row.cpp);
// at 1 this frees it from rest, at 2 also when it arrives at 10 m/s at 10 ms x 3. On Vajont
// (10 ms x 3, slop 0.25 mm) 2 |g| h^2 = 0.22 mm stays under the slop: its runs are unchanged
// (model revision 2026-12-04.1).
inline constexpr double kSagRatio = 2.0;

// The slop (CollideSettings::linear_slop) as a share of the largest move a block may make per
// step: an overlap that small is tolerated without push-out (substep solver) or a change of
// contact state (implicit solver), since a contact pushed out to exactly zero chatters between
// touching and not; it is also the separating-axis tolerance of the manifold.
inline constexpr double kLinearSlopRatio = 1e-3;

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
  // m, >= 0: how deep a block can rest in its supports beyond the slop because the solver steps
  // (the substep solver: kSagRatio |g| h^2, h its longest substep; 0 for the implicit solver).
  // "Proud edges" (manifold.hpp) reads edges up to max(linear_slop, proud floor, sag) proud.
  double sag = 0.0;
  // s: the (sub)step over which a face that meets sliding first acts (predict_first_slip,
  // slip_history.hpp); 0 (the starts before the clock runs): no prediction.
  double slip_step = 0.0;
};

// A run's tolerances, for blocks that move at most `max_move` per step: points kept while their
// gap is under search_distance_factor x max_move, and the slop above. Both solvers' starts
// (run_implicit.cpp, run_substep.cpp) and the tall-slider test at t = 0 (common/known_limits.cpp).
inline void set_run_tolerances(CollideSettings& settings, double search_distance_factor, double max_move) {
  settings.margin = search_distance_factor * max_move;
  settings.linear_slop = kLinearSlopRatio * max_move;
}

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
