#include "forward/step/check_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "forward/contact_geometry.hpp"
#include "forward/friction.hpp"

namespace ddafit {

ContactCheck check_contacts(const BlockSystem& s, std::vector<Contact>& contacts, const Eigen::VectorXd& d,
                            const StepParameters& step) {
  ContactCheck result;
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
    const double tension_cap = c.bonded ? face.tensile_strength * c.bond_length : 0.0;
    const double compression = -step.penalty * c.normal_gap;  // N, negative in tension

    if (-compression > tension_cap) {
      c.state = ContactState::Open;
      c.normal_force = 0.0;
    } else {
      c.normal_force = std::max(compression, 0.0);
      if (before == ContactState::Sliding) {
        // A sliding contact stays sliding while it keeps slipping the same way
        // (sliding_slip: measured so that a spring letting go is not read as a
        // backward slip). A contact on the point of sticking has a slip of round-off
        // size of either sign; the small allowance (1 % of the elastic offset that the
        // friction force gives the shear spring, and at least 1e-9 of the edge length
        // for frictionless contacts) stops it flipping between sliding and locked from
        // one pass to the next.
        const double allowance =
            0.01 * sliding_friction_force(s, c) / step.shear_penalty + 1e-9 * lin.edge_length;
        if (sliding_slip(c) * c.slip_direction <= -allowance) c.state = ContactState::Locked;
      } else {
        // Locked (or just closed): the shear spring must stay within Mohr-Coulomb.
        const double cohesion = c.bonded ? face.cohesion * c.bond_length : 0.0;
        const double limit = sliding_friction_force(s, c) + cohesion;
        const double shear = step.shear_penalty * c.shear_offset;
        if (std::abs(shear) <= limit) {
          c.state = ContactState::Locked;
        } else {
          c.state = ContactState::Sliding;
          c.slip_direction = shear > 0.0 ? 1.0 : -1.0;
        }
      }
    }
    if (c.state != before) {
      ++result.changed;
      if (result.first_changed < 0) result.first_changed = k;
    } else if (c.state == ContactState::Sliding) {
      // Only sliding contacts feed N back into the load vector.
      const double scale = std::max({c.normal_force, force_before, 1e-300});
      result.max_force_change = std::max(result.max_force_change, std::abs(c.normal_force - force_before) / scale);
    }
  }
  return result;
}

}  // namespace ddafit
