#include "forward/step/check_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "forward/contact_geometry.hpp"
#include "forward/contact_law.hpp"

namespace ddafit {

ContactCheck check_contacts(const BlockSystem& s, std::vector<Contact>& contacts, const Eigen::VectorXd& d,
                            const StepParameters& step) {
  ContactCheck result;
  double largest_change = 0.0, largest_force = 0.0;
  for (int k = 0; k < static_cast<int>(contacts.size()); ++k) {
    Contact& c = contacts[k];
    const Block& bi = s.blocks[c.block_i];
    const Block& bj = s.blocks[c.block_j];
    const ContactLinearization lin = linearize_contact(s, c);
    c.normal_gap = (lin.area0 + contact_form(lin.e, lin.g, bi, bj, d)) / lin.edge_length;
    c.step_slip = contact_form(lin.es, lin.gs, bi, bj, d);
    c.shear_offset = lin.shear0 + c.step_slip;

    const ContactState before = c.state;
    const double force_before = c.normal_force;
    const Interface& face = s.interfaces[c.interface];
    const double tension_cap = tensile_capacity(face, c.bonded, c.bond_length);
    // N, negative in tension; the spring is unloaded at spring_reference (assemble.hpp).
    const double compression = -step.penalty * (c.normal_gap - spring_reference(c, step));

    const bool stays_open = before == ContactState::Open && c.normal_gap > -step.contact_tolerance;
    if (-compression > tension_cap || stays_open) {
      c.state = ContactState::Open;
      c.normal_force = 0.0;
    } else {
      c.normal_force = std::max(compression, 0.0);
      if (before == ContactState::Sliding) {
        // A sliding contact stays sliding while it keeps slipping the same way
        // (sliding_slip: measured so that a spring letting go is not read as a
        // backward slip). A contact on the point of sticking has a slip of round-off
        // size of either sign; the allowance (the contact tolerance, plus 1 % of the
        // elastic offset that the friction force gives the shear spring) stops it
        // flipping between sliding and locked from one pass to the next.
        const double allowance =
            step.contact_tolerance + 0.01 * sliding_friction_force(s, c) / step.shear_penalty;
        if (sliding_slip(c) * c.slip_direction <= -allowance) c.state = ContactState::Locked;
      } else {
        // Locked (or just closed): the shear spring must stay within Mohr-Coulomb.
        const double limit = locked_shear_limit(s, c);
        const double shear = step.shear_penalty * c.shear_offset;
        if (std::abs(shear) <= limit) {
          c.state = ContactState::Locked;
        } else {
          c.state = ContactState::Sliding;
          c.slip_direction = shear > 0.0 ? 1.0 : -1.0;
        }
      }
    }
    // A contact that has cycled between states within the step keeps its state for the
    // rest of the step: its gap and slip swing by small amounts as its neighbours change.
    // The one exception is closing: a contact held open while it penetrates lets the
    // vertex run into the block unopposed, and the spring releases that overlap as energy
    // once it closes (a tiled 1500-block mass blew up at its first step when cycling
    // corners were held open at 7 mm of penetration). Closing wins, so every contact can
    // change from open to closed but not back, and the iteration still settles.
    const bool closing = before == ContactState::Open && c.state != ContactState::Open;
    if (c.state != before && c.state_changes >= kFreezeAfterChanges && !closing) {
      c.state = before;
      c.normal_force = before == ContactState::Open ? 0.0 : std::max(compression, 0.0);
      ++result.frozen;
    }
    if (c.state != before) {
      ++c.state_changes;
      ++result.changed;
      if (result.first_changed < 0) result.first_changed = k;
    } else if (c.state == ContactState::Sliding) {
      // Only sliding contacts feed N back into the load vector.
      largest_change = std::max(largest_change, std::abs(c.normal_force - force_before));
    }
    largest_force = std::max(largest_force, c.normal_force);
  }
  // Relative to the largest contact force: a nearly unloaded contact whose N changes by
  // half of nothing does not hold up the iteration.
  result.max_force_change = largest_force > 0.0 ? largest_change / largest_force : 0.0;
  return result;
}

}  // namespace ddafit
