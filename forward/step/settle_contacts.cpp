#include "forward/step/settle_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/common/displace_block.hpp"
#include "forward/common/supported_blocks.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/kinematics.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/new_points.hpp"
#include "forward/step/point_springs.hpp"
#include "forward/step/settle_sliding.hpp"

namespace ddafit {

// The contacts now carry the static load; their springs start from here. Settling holds
// every point locked, so where friction cannot hold the slope the shear springs store the
// excess; released in the first step it throws blocks at metres per second (9 m/s in the
// Vajont section). Such points start sliding instead, their springs at the friction limit:
// the slide then starts from rest, as it should.
void load_springs(const BlockSystem& s, ContactSet& contacts, const StepParameters& step) {
  for (ContactManifold& m : contacts.manifolds) {
    const Interface& face = s.interfaces[m.interface];
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      SpringState& c = p.spring;
      c.normal_gap = p.separation;
      c.step_slip = 0.0;
      c.normal_force = c.state == ContactState::Open ? 0.0 : std::max(0.0, -step.penalty * p.separation);
      if (c.state == ContactState::Open) continue;
      const double limit = coulomb_cap(m.friction, c.normal_force, cohesive_strength(face, p));
      const double shear = step.shear_penalty * c.shear_offset;
      // Blocks given a velocity slide past each other from the start: locked, the spring
      // would grab a block thrown at 4 m/s within the first step (new_points.hpp).
      const double slide = relative_slide(s, m, p) * step.time_step;
      if (std::abs(slide) > step.contact_tolerance) {
        c.slip_direction = slide > 0.0 ? 1.0 : -1.0;
      } else if (std::abs(shear) > limit) {
        c.slip_direction = shear > 0.0 ? 1.0 : -1.0;
      } else {
        continue;
      }
      c.state = ContactState::Sliding;
      c.shear_offset = sliding_shear_offset(face, m, p, step.shear_penalty);
    }
  }
}

std::string apply_settling_pass(ImplicitStepContext& ctx, const Eigen::VectorXd& d, const std::vector<char>& moves) {
  BlockSystem& s = ctx.system;
  // The locked springs' offsets follow the pass; settling is not part of the measured motion,
  // so the points' origins move with the blocks.
  Eigen::VectorXd moved = d;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (s.blocks[b].unknown >= 0 && !moves[b]) moved.segment<6>(6 * s.blocks[b].unknown).setZero();
  for (ContactManifold& m : ctx.contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      if (p.spring.state != ContactState::Locked) continue;
      const PointSprings lin = point_springs(s, m, p);
      p.spring.shear_offset +=
          lin.shear_move(block_step(s.blocks[m.block_a], moved), block_step(s.blocks[m.block_b], moved));
    }
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (s.blocks[b].unknown >= 0 && moves[b])
      displace_block(s, b, moved.segment<6>(6 * s.blocks[b].unknown), false);
  ctx.detection.settings.first_step = true;  // points new and touching lock
  return detect_contacts(s, ctx.detection, ctx.contacts);
}

namespace {

// A block whose pass moves it at least this share of its move in the pass before is falling,
// not settling: on its way to equilibrium every pass shrinks the distance by the factor of
// settle_contacts.hpp (under 0.5 on the 225 m Vajont mass), while a block released on its
// corner falls further in each pass than in the last (a 1 x 4.5 m block tilted 0.11 rad:
// 7.2, 8.3, 9.4 ... cm per pass, set upright before t = 0 until revision 2026-12-03.1).
constexpr double kFallingRatio = 0.9;
// ... and turns about a point it rests on: its smallest move at its closed contact points is
// under this share of its largest move. A block sinking further each pass into springs far
// too soft (a penalty of 1000 N/m under a 12 t/m slider) moves as much there as anywhere,
// and is left to settle, sink and be stopped by the penetration check with its diagnosis.
constexpr double kPivotShare = 0.5;
// A block that a single pass turns by more than this (rad) about a point it rests on falls
// too: settling is elastic, and turns a block by a strain's worth (2.7e-5 rad at most on
// Vajont section I, 2.8e-4 on VII), while a column of fourteen 0.5 x 0.16 m blocks tilted
// 0.011 rad was set upright in the first pass.
constexpr double kFallingTurn = 3e-3;
// Restarts of the settling without the blocks found falling (each restart frees at least one).
constexpr int kFallingRestarts = 4;

enum class Settled { Done, Failed, Falling };

// The blocks touching a falling block fall with it (each joined through free blocks): a column
// whose upper blocks were held as given while its base block settled overlapped itself and
// bounced apart in the first step (fourteen 0.5 x 0.11 m blocks tilted 0.016 rad).
void fall_with_neighbours(const BlockSystem& s, const ContactSet& contacts, std::vector<char>& falling) {
  for (bool grew = true; grew;) {
    grew = false;
    for (const ContactManifold& m : contacts.manifolds) {
      const int a = m.block_a, b = m.block_b;
      if (s.blocks[a].unknown < 0 || s.blocks[b].unknown < 0 || falling[a] == falling[b]) continue;
      falling[a] = falling[b] = 1;
      grew = true;
    }
  }
}

// The passes (settle_contacts below) for the blocks in `settles`, none of `falling`; on a
// falling block, returns Falling with the newly falling ones flagged and nothing undone.
Settled run_passes(ImplicitStepContext& ctx, const StepParameters& relaxed, double max_shift, std::vector<char>& settles,
                   std::vector<char>& falling, std::string& problem) {
  BlockSystem& s = ctx.system;
  ContactDetection& detection = ctx.detection;
  ContactSet& contacts = ctx.contacts;
  GlobalSystem eq;  // its own: the relaxed step's K and F are not the dynamic ones
  const Eigen::VectorXd& d = eq.d;
  bool converged_closed = true;  // no point closed in the last pass
  // The falling test's floor: moves under the contact slop are settling's own noise.
  const double noise = detection.settings.linear_slop;
  std::vector<double> last(s.blocks.size(), 0.0), at_contacts(s.blocks.size(), 0.0);
  for (int pass = 0; pass < ctx.options.settle_passes; ++pass) {
    assemble(s, contacts, relaxed, eq);
    std::string reason;
    if (!ctx.solver.solve(eq.k, eq.f, eq.d, reason)) return Settled::Failed;
    const auto moving = [&](int b) { return s.blocks[b].unknown >= 0 && settles[b] && !falling[b]; };
    const auto unknowns = [&](int b) -> Vec6 { return d.segment<6>(6 * s.blocks[b].unknown); };
    // Each block's smallest move at its closed contact points: one turning about a point it
    // rests on hardly moves there.
    std::fill(at_contacts.begin(), at_contacts.end(), std::numeric_limits<double>::infinity());
    for (const ContactManifold& m : contacts.manifolds)
      for (int q = 0; q < m.point_count; ++q) {
        if (m.points[q].spring.state == ContactState::Open) continue;
        for (const int b : {m.block_a, m.block_b})
          if (moving(b))
            at_contacts[b] = std::min(at_contacts[b], exact_point_displacement(m.points[q].anchor, s.blocks[b].centroid,
                                                                               unknowns(b)).norm());
      }
    double largest = 0.0;
    bool fell = false;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
      if (!moving(b)) continue;
      const double move = block_displacement(s, b, unknowns(b));
      const bool grows = pass > 0 && move > noise && move >= kFallingRatio * last[b];
      const bool turns = std::abs(unknowns(b)[2]) > kFallingTurn;
      if ((grows || turns) && at_contacts[b] < kPivotShare * move) falling[b] = 1, fell = true;
      last[b] = move;
      largest = std::max(largest, move);
    }
    if (fell) {
      fall_with_neighbours(s, contacts, falling);
      return Settled::Falling;
    }
    if (largest > max_shift) break;
    const bool converged = largest <= kSettleTolerance * max_shift;
    std::vector<char> moves(s.blocks.size(), 0);
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) moves[b] = moving(b);
    // A point that was open and now penetrates closes (locked where it is, no shear
    // offset), or the next pass would let the blocks sink through each other and the first
    // dynamic step would fire them apart.
    problem = apply_settling_pass(ctx, d, moves);
    if (!problem.empty()) return Settled::Done;
    // (A point new in this detection that touches was locked by the detection itself.)
    for (ContactManifold& m : contacts.manifolds)
      for (int q = 0; q < m.point_count; ++q) {
        ContactPoint& p = m.points[q];
        const bool closes = p.spring.state == ContactState::Open && p.separation <= detection.settings.linear_slop;
        if (!closes && !(p.fresh && p.spring.state != ContactState::Open)) continue;
        p.spring.state = ContactState::Locked;
        p.spring.shear_offset = 0.0;
        settles[m.block_a] = settles[m.block_b] = 1;
        converged_closed = false;
      }
    if (converged && converged_closed) break;
    converged_closed = true;
  }
  return Settled::Done;
}

}  // namespace

bool settle_contacts(ImplicitStepContext& ctx, const StepParameters& step, double max_shift, std::string& problem) {
  BlockSystem& s = ctx.system;
  StepParameters relaxed = step;
  relaxed.time_step = std::max(step.time_step * kSettleStepScale,
                               kSettlePeriods * longest_elastic_period(ctx.scene, s));
  // The push-out cap is a speed (assemble.hpp, spring_reference): over the passes' longer step.
  relaxed.pushout = step.pushout * (relaxed.time_step / step.time_step);
  // The blocks that settle: those resting on the ground (a cluster touching only itself is in
  // flight), and those a pass brings into contact with them.
  const std::vector<char> supported = supported_blocks(s, ctx.contacts.manifolds, ctx.detection.settings.linear_slop);
  std::vector<Vec6> velocities(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    velocities[b] = s.blocks[b].velocity;
    s.blocks[b].velocity.setZero();
  }
  // What a restart goes back to: a falling block starts where it was given, as one in flight
  // does, and the others settle again without it.
  const std::vector<Block> blocks = s.blocks;
  const std::vector<Vec2> vertices = s.vertices;
  const std::vector<MaterialPoint> points = s.points;
  const ContactSet contacts = ctx.contacts;
  std::vector<char> falling(s.blocks.size(), 0), settles;
  Settled result = Settled::Done;
  bool as_given = false;
  for (int attempt = 0; attempt <= kFallingRestarts; ++attempt) {
    settles = supported;
    result = run_passes(ctx, relaxed, max_shift, settles, falling, problem);
    if (result != Settled::Falling) break;
    s.blocks = blocks, s.vertices = vertices, s.points = points, ctx.contacts = contacts;
    for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity.setZero();
    if (attempt == kFallingRestarts) result = Settled::Done, as_given = true;  // the state as given
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity = velocities[b];
  load_springs(s, ctx.contacts, step);
  if (result == Settled::Done && !as_given && problem.empty()) {
    // The blocks that start sliding, settled again as they slide (settle_sliding.hpp).
    std::vector<char> settled(s.blocks.size(), 0);
    for (size_t b = 0; b < s.blocks.size(); ++b) settled[b] = settles[b] && !falling[b];
    settle_sliding_groups(ctx, relaxed, step, settled, max_shift);
  }
  return result != Settled::Failed;
}

}  // namespace ddafit
