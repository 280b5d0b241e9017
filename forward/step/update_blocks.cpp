#include "forward/step/update_blocks.hpp"

#include <cmath>

#include "forward/common/displace_block.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/point_springs.hpp"

namespace ddafit {

void update_blocks(ImplicitStepContext& ctx, double dt) {
  BlockSystem& s = ctx.system;
  ContactSet& contacts = ctx.contacts;
  const Eigen::VectorXd& d = ctx.equations.d;
  const double shear_penalty = ctx.options.shear_penalty_ratio * ctx.control.penalty;
  for (int bid = 0; bid < static_cast<int>(s.blocks.size()); ++bid) {
    Block& b = s.blocks[bid];
    if (b.unknown < 0) continue;
    const Vec6 db = d.segment<6>(6 * b.unknown);
    // Constant acceleration over the step: V1 = 2 D / dt - V0.
    b.velocity = (2.0 / dt) * db - b.velocity;
    displace_block(s, bid, db, true);
  }
  for (ContactManifold& m : contacts.manifolds) {
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      SpringState& c = p.spring;
      p.slip = 0.0;
      p.normal_load = c.state == ContactState::Open ? 0.0 : std::max(c.normal_force, 0.0);
      if (c.state == ContactState::Locked) {
        c.shear_offset += c.step_slip;  // the spring keeps its offset
        continue;
      }
      break_bond(p);
      if (c.state == ContactState::Sliding) {
        p.slip = std::abs(sliding_slip(c));  // seed Eq. 2
        // The spring trails the slip by the friction force over its stiffness, so that
        // should the point lock in the next step, its spring takes over at the friction
        // force instead of at zero: a sudden loss of resistance at every stick feeds
        // stick-slip vibration at short time steps.
        c.shear_offset = c.slip_direction * sliding_friction_force(m, p) / shear_penalty;
      } else {
        c.shear_offset = 0.0;
      }
    }
  }
  advance_histories(s, contacts, dt);
}

}  // namespace ddafit
