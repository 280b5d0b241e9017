#include "forward/step/update_blocks.hpp"

#include <cmath>

#include "forward/common/displace_block.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/point_springs.hpp"

namespace ddafit {
namespace {

// A step whose velocity update turns a block's motion round with a change of more than
// this many |g| dt was an impulsive stop (gravity and Coulomb friction change a velocity by
// about |g| dt per step; nothing but an impact or a jam does it twice as fast).
constexpr double kImpulsiveStop = 2.0;

}  // namespace

// Constant acceleration (Shi 1993): V1 = 2 D / dt - V0. A block stopped within the step by
// impulsive contact forces (a jam: a sliding row wedged against the floor; an impact the
// impulses of resolve_impacts.hpp did not see) has D ~ 0, and the same rule gives
// V1 ~ -V0, a perfectly elastic bounce: the row of tall blocks of
// tests/test_impact_rebound.cpp came back at 0.4 of its speed, the floor handing it more
// momentum than its friction can. A rock impact is inelastic (docs/theory.md §3), so a
// block whose translation the step reverses impulsively takes the step's mean velocity
// D / dt instead; its kinetic energy is then below half the larger of the two rules'.
Vec6 step_velocity(const Block& b, const Vec6& d, double dt, double gravity) {
  const Vec6 v1 = (2.0 / dt) * d - b.velocity;
  const Vec2 before = b.velocity.head<2>(), after = v1.head<2>();
  const bool impulsive_stop = after.dot(before) < 0.0 && (after - before).norm() > kImpulsiveStop * gravity * dt;
  return impulsive_stop ? Vec6(d / dt) : v1;
}

void update_blocks(ImplicitStepContext& ctx, double dt) {
  BlockSystem& s = ctx.system;
  ContactSet& contacts = ctx.contacts;
  const Eigen::VectorXd& d = ctx.equations.d;
  const double shear_penalty = ctx.options.shear_penalty_ratio * ctx.control.penalty;
  for (int bid = 0; bid < static_cast<int>(s.blocks.size()); ++bid) {
    Block& b = s.blocks[bid];
    if (b.unknown < 0) continue;
    const Vec6 db = d.segment<6>(6 * b.unknown);
    b.velocity = step_velocity(b, db, dt, ctx.scene.gravity.norm());
    displace_block(s, bid, db, true);
  }
  const double slop = ctx.detection.settings.linear_slop;
  for (ContactManifold& m : contacts.manifolds) {
    const Interface& face = s.interfaces[m.interface];
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      SpringState& c = p.spring;
      p.slip = 0.0;
      p.normal_load = c.state == ContactState::Open ? 0.0 : std::max(c.normal_force, 0.0);
      if (c.state == ContactState::Locked && c.shear_scale == 1.0f) {
        c.shear_offset += c.step_slip;  // the spring keeps its offset
        continue;
      }
      double slip = 0.0;  // signed, at strength
      if (c.state == ContactState::Locked) {
        // A capped lock (check_contacts.cpp): its spring carries the force of the softened
        // one, k_s' (d_s0 + d_s), as an offset at full stiffness; the rest of the move is
        // slip (seed Eq. 2), as for a sliding point.
        const double moved = c.shear_offset + c.step_slip;
        c.shear_offset = c.shear_scale * moved;
        slip = moved - c.shear_offset;
      } else if (c.state == ContactState::Sliding) {
        slip = sliding_slip(c);  // seed Eq. 2
      }
      p.slip = std::abs(slip);
      // The bond goes once the point has slid or opened at its strength by more than the slop
      // (contact_law.hpp, wear_bond): sliding and capped points are at it, and open ones
      // (the tension cut-off), which opened by the step's change of gap.
      wear_bond(p, slip, c.state == ContactState::Open ? c.normal_gap - p.separation : 0.0, slop);
      if (c.state == ContactState::Sliding) {
        c.shear_offset = sliding_shear_offset(face, m, p, shear_penalty);  // pre-loaded for a lock
      } else if (c.state == ContactState::Open) {
        c.shear_offset = 0.0;
      }
    }
  }
  advance_histories(s, contacts, dt);
}

}  // namespace ddafit
