#include "forward/step/settle_contacts.hpp"

#include <algorithm>

#include "forward/common/displace_block.hpp"
#include "forward/common/supported_blocks.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/new_points.hpp"
#include "forward/step/point_springs.hpp"

namespace ddafit {
namespace {

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
      break_bond(p);
      c.shear_offset = sliding_shear_offset(m, p, step.shear_penalty);
    }
  }
}

}  // namespace

bool settle_contacts(ImplicitStepContext& ctx, const StepParameters& step, double max_shift, std::string& problem) {
  BlockSystem& s = ctx.system;
  ContactDetection& detection = ctx.detection;
  ContactSet& contacts = ctx.contacts;
  const int passes = ctx.options.settle_passes;
  StepParameters relaxed = step;
  relaxed.time_step *= kSettleStepScale;
  // The blocks that settle: those resting on the ground (a cluster touching only itself is in
  // flight), and those a pass brings into contact with them.
  std::vector<char> settles = supported_blocks(s, contacts.manifolds, detection.settings.linear_slop);

  std::vector<Vec6> velocities(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    velocities[b] = s.blocks[b].velocity;
    s.blocks[b].velocity.setZero();
  }
  GlobalSystem eq;  // its own: the relaxed step's K and F are not the dynamic ones
  const Eigen::VectorXd& d = eq.d;
  bool ok = true;
  bool converged_closed = true;  // no point closed in the last pass
  for (int pass = 0; pass < passes && ok; ++pass) {
    assemble(s, contacts, relaxed, eq);
    std::string reason;
    ok = ctx.solver.solve(eq.k, eq.f, eq.d, reason);
    if (!ok) break;
    const auto moving = [&](int b) { return s.blocks[b].unknown >= 0 && settles[b]; };
    const auto unknowns = [&](int b) -> Vec6 { return d.segment<6>(6 * s.blocks[b].unknown); };
    double largest = 0.0;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (moving(b)) largest = std::max(largest, block_displacement(s, b, unknowns(b)));
    if (largest > max_shift) break;
    const bool converged = largest <= kSettleTolerance * max_shift;
    // The locked springs' offsets follow the pass; settling is not part of the measured
    // motion, so the points' origins move with the blocks.
    Eigen::VectorXd moved = d;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (s.blocks[b].unknown >= 0 && !moving(b)) moved.segment<6>(6 * s.blocks[b].unknown).setZero();
    for (ContactManifold& m : contacts.manifolds)
      for (int q = 0; q < m.point_count; ++q) {
        ContactPoint& p = m.points[q];
        if (p.spring.state == ContactState::Open) continue;
        const PointSprings lin = point_springs(s, m, p);
        p.spring.shear_offset += lin.shear_move(block_step(s.blocks[m.block_a], moved), block_step(s.blocks[m.block_b], moved));
      }
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (moving(b)) displace_block(s, b, unknowns(b), false);
    // A point that was open and now penetrates closes (locked where it is, no shear
    // offset), or the next pass would let the blocks sink through each other and the first
    // dynamic step would fire them apart.
    detection.settings.first_step = true;
    problem = detect_contacts(s, detection, contacts);
    detection.settings.first_step = true;
    if (!problem.empty()) return true;
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
  for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity = velocities[b];
  load_springs(s, contacts, step);
  return ok;
}

}  // namespace ddafit
