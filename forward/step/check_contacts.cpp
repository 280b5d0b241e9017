#include "forward/step/check_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "forward/contact/contact_law.hpp"
#include "forward/contact/corner_paths.hpp"
#include "forward/step/point_springs.hpp"

namespace ddafit {
namespace {

// A capped lock asks for another pass while its spring is softened by more than 1 % and by
// more than the contact tolerance of slip (cap_lock below).
constexpr double kCapTolerance = 1.01;

// Classifies one point from this iterate's gap and slip (the contact law, Mohr-Coulomb).
void classify(const Interface& face, const ContactManifold& m, ContactPoint& p, double compression,
              const StepParameters& step, bool passing) {
  SpringState& c = p.spring;
  const ContactState before = c.state;
  const bool stays_open = before == ContactState::Open && (c.normal_gap > -step.contact_tolerance || passing);
  if (-compression > tensile_capacity(face, p) || stays_open) {  // tension cut-off
    c.state = ContactState::Open;
    c.normal_force = 0.0;
    return;
  }
  c.normal_force = std::max(compression, 0.0);
  if (before == ContactState::Open) {
    // Just closed. Its normal force is that of an iterate in which nothing held the blocks
    // apart there (an impact read 3.4 MN/m where the closed spring carries a fraction of
    // it): as a friction force for the next iterate it threw a wedge landing on a corner
    // back at 1.4 m/s. So the next iterate has no friction from it: the point slides the
    // way it moved in this iterate (a landing with tangential speed is a sliding impact),
    // or locks if it hardly moved; the iterate after, with its spring in place, has the
    // real normal force. Locked at once, it stopped a block landing at 2 m/s dead in one
    // step, and the sign of the rebound it gave the shear spring became the slide's.
    c.normal_force = 0.0;
    if (std::abs(c.step_slip) > step.contact_tolerance) {
      c.state = ContactState::Sliding;
      c.slip_direction = c.step_slip > 0.0 ? 1.0 : -1.0;
    } else {
      c.state = ContactState::Locked;
    }
    return;
  }
  if (before == ContactState::Sliding) {
    // A sliding point stays sliding while it keeps slipping the same way (sliding_slip:
    // measured so that a spring letting go is not read as a backward slip). A point on the
    // point of sticking has a slip of round-off size of either sign; the allowance (the
    // contact tolerance, plus 1 % of the elastic offset that the friction force gives the
    // shear spring) stops it flipping between sliding and locked from one pass to the next.
    const double allowance = step.contact_tolerance + 0.01 * sliding_friction_force(face, m, p) / step.shear_penalty;
    if (sliding_slip(c) * c.slip_direction <= -allowance) c.state = ContactState::Locked;
    return;
  }
  // Locked (or just closed): the shear spring must stay within Mohr-Coulomb.
  const double limit = coulomb_cap(m.friction, c.normal_force, cohesive_strength(face, p));
  const double shear = locked_shear_stiffness(c, step) * (c.shear_offset + c.step_slip);
  if (std::abs(shear) <= limit) {
    c.state = ContactState::Locked;
  } else {
    c.state = ContactState::Sliding;
    c.slip_direction = shear > 0.0 ? 1.0 : -1.0;
  }
}

// Capped locks. A point frozen locked (it has changed state twice this step) whose shear
// spring pulls harder than its Coulomb cap, |k_s (d_s0 + d_s)| > N tan(phi) + c l, keeps its
// state but not its stiffness: the spring is softened to the share that carries the cap,
// k_s' = k_s limit / |shear|, for the rest of the step (update_blocks.cpp then takes the rest
// of its offset as slip). Held at full stiffness, such points (the rear corners of a slider
// over short blocks, whose slip turns with the slider's elastic strain while the whole
// slider barely moves, a step from rest) held a slider 25 times past their cap and stopped it
// on a slope steeper than its friction (docs/theory.md, Known limits (g)). Let slide instead,
// they cycled again. Returns whether the softening asks for another pass (ContactCheck::capped):
// by more than 1 % and by more than the contact tolerance of slip. Not asked, sliders over
// short blocks fell up to 1.7 % behind seed Eq. 4; counted as state changes, the settling
// courses of standing brick walls still "changed" at the pass limit, and the steps were cut (6
// cuts in 10 ms on 100 bricks), which is why they only hold the iteration open.
bool cap_lock(const Interface& face, const ContactManifold& m, ContactPoint& p, const StepParameters& step,
              double& excess) {
  SpringState& c = p.spring;
  const double limit = coulomb_cap(m.friction, c.normal_force, cohesive_strength(face, p));
  const double stiffness = locked_shear_stiffness(c, step);
  const double shear = std::abs(stiffness * (c.shear_offset + c.step_slip));
  if (!(shear > limit)) return false;
  excess = std::max(excess, shear - limit);
  c.shear_scale = static_cast<float>(c.shear_scale * (limit / shear));
  return shear > kCapTolerance * limit && (shear - limit) / stiffness > step.contact_tolerance;
}

// A block slower at the step's start than kStartingSpeedRatio |g| dt (its centroid's speed;
// a fixed block's is zero).
bool starting(const Block& b, const StepParameters& step) {
  return b.velocity.head<2>().norm() <= kStartingSpeedRatio * step.gravity.norm() * step.time_step;
}

}  // namespace

ContactCheck check_contacts(const BlockSystem& s, const ContactShapes& shapes, double slop, ContactSet& contacts,
                            const Eigen::VectorXd& d, const StepParameters& step) {
  ContactCheck result;
  double largest_change = 0.0, largest_force = 0.0, cap_excess = 0.0;
  for (int k = 0; k < static_cast<int>(contacts.manifolds.size()); ++k) {
    ContactManifold& m = contacts.manifolds[k];
    const Vec6 da = block_step(s.blocks[m.block_a], d), db = block_step(s.blocks[m.block_b], d);
    const Interface& face = s.interfaces[m.interface];
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      SpringState& c = p.spring;
      const PointSprings lin = point_springs(s, m, p);
      c.normal_gap = lin.gap0 + lin.normal_move(da, db);
      c.step_slip = lin.shear_move(da, db);
      const ContactState before = c.state;
      const double force_before = c.normal_force;
      // N, negative in tension; the spring is unloaded at spring_reference (assemble.hpp).
      const double compression = -step.penalty * (c.normal_gap - spring_reference(p, step));
      // Two corners passing each other over the step's move (D's rigid part) meet nowhere.
      const bool passing = c.state == ContactState::Open && apart_corners(m, p) &&
                           corners_pass(s, shapes, m, p, p.separation, Vec3::Zero(), Vec3::Zero(), da.head<3>(),
                                        db.head<3>(), 1.0, slop);
      classify(face, m, p, compression, step, passing);
      // A point that has cycled between states within the step keeps its state for the
      // rest of the step: its gap and slip swing by small amounts as its neighbours change.
      // The one exception is closing: a point held open while it penetrates lets the
      // block run into the other unopposed, and the spring releases that overlap as energy
      // once it closes (a tiled 1500-block mass blew up at its first step when cycling
      // corners were held open at 7 mm of penetration). Closing wins, so every point can
      // change from open to closed but not back, and the iteration still settles. Locking
      // wins too: a sliding point locks only when its slip has turned against its friction
      // force, and held sliding it would push the blocks along (friction doing work on them:
      // a stack of five blocks rocked itself over that way).
      // And opening wins where the gap is open by more than the contact tolerance: held
      // closed, the spring pulls the blocks together, a glue no rock joint has. Until revision
      // 2026-11-28.1 it did: a frozen point under 5 MN/m of tension held a row of tall blocks
      // down at one end while the other end's corner took 5 MN/m of compression, whose
      // friction stopped the sliding row within a step, and the step's velocity update then
      // threw the row back at 0.4 of its speed (tests/test_impact_rows.cpp, free rows).
      const bool closing = before == ContactState::Open && c.state != ContactState::Open;
      const bool locking = before == ContactState::Sliding && c.state == ContactState::Locked;
      const bool opening = before != ContactState::Open && c.state == ContactState::Open &&
                           c.normal_gap > step.contact_tolerance;
      if (c.state != before && c.state_changes >= kFreezeAfterChanges && !closing && !locking && !opening) {
        c.state = before;
        c.normal_force = before == ContactState::Open ? 0.0 : std::max(compression, 0.0);
        ++result.frozen;
        if (before == ContactState::Locked && cap_lock(face, m, p, step, cap_excess)) {
          ++result.capped;
          if (starting(s.blocks[m.block_a], step) && starting(s.blocks[m.block_b], step)) ++result.capped_starting;
        }
      }
      if (c.state != before) {
        ++c.state_changes;
        ++result.changed;
        if (result.first_changed.manifold < 0) result.first_changed = {k, q};
      } else if (c.state == ContactState::Sliding) {
        // Only sliding points feed N back into the load vector.
        largest_change = std::max(largest_change, std::abs(c.normal_force - force_before));
      }
      largest_force = std::max(largest_force, c.normal_force);
    }
  }
  // Relative to the largest contact force: a nearly unloaded point whose N changes by
  // half of nothing does not hold up the iteration.
  result.max_force_change = largest_force > 0.0 ? largest_change / largest_force : 0.0;
  result.cap_excess = largest_force > 0.0 ? cap_excess / largest_force : 0.0;
  return result;
}

}  // namespace ddafit
