#include "forward/step/settle_contacts.hpp"

#include <algorithm>

#include "forward/contact_geometry.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/update_blocks.hpp"

namespace ddafit {

bool settle_contacts(BlockSystem& s, std::vector<Contact>& contacts, const StepParameters& step, int passes,
                     double max_shift, SparseSolver& solver) {
  StepParameters relaxed = step;
  relaxed.time_step *= kSettleStepScale;
  std::vector<char> touching(s.blocks.size(), 0);
  for (const Contact& c : contacts)
    if (c.state != ContactState::Open) touching[c.block_i] = touching[c.block_j] = 1;

  std::vector<Vec6> velocities(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    velocities[b] = s.blocks[b].velocity;
    s.blocks[b].velocity.setZero();
  }
  BlockSparseMatrix k;
  Eigen::VectorXd f, d;
  bool ok = true;
  bool converged_closed = true;  // no contact closed in the last pass
  for (int pass = 0; pass < passes && ok; ++pass) {
    assemble(s, contacts, relaxed, k, f);
    std::string reason;
    ok = solver.solve(k, f, d, reason);
    if (!ok) break;
    const auto moving = [&](int b) { return s.blocks[b].unknown >= 0 && touching[b]; };
    const auto unknowns = [&](int b) -> Vec6 { return d.segment<6>(6 * s.blocks[b].unknown); };
    double largest = 0.0;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (moving(b)) largest = std::max(largest, block_displacement(s, b, unknowns(b)));
    if (largest > max_shift) break;
    const bool converged = largest <= kSettleTolerance * max_shift;
    // Settling is not part of the measured motion: the points' origins move too.
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (moving(b)) displace_block(s, b, unknowns(b), false);
    // A contact that was open at t = 0 and now penetrates closes (locked where it
    // is), or the next pass would let the blocks sink through each other and the first
    // dynamic step would fire them apart.
    for (Contact& c : contacts) {
      if (c.state != ContactState::Open) continue;
      const ContactLinearization lin = linearize_contact(s, c);
      if (lin.area0 >= 0.0) continue;
      c.state = ContactState::Locked;
      c.reference_ratio += lin.shear0 / lin.edge_length;  // P0 under the vertex: no shear offset
      touching[c.block_i] = touching[c.block_j] = 1;
      converged_closed = false;
    }
    if (converged && converged_closed) break;
    converged_closed = true;
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity = velocities[b];
  // The contacts now carry the static load; their springs start from here. Settling
  // holds every contact locked, so where friction cannot hold the slope the shear
  // springs store the excess; released in the first step it throws blocks at metres per
  // second (9 m/s in the Vajont section). Such contacts start sliding instead, their
  // springs at the friction limit: the slide then starts from rest, as it should.
  for (Contact& c : contacts) {
    const ContactLinearization lin = linearize_contact(s, c);
    c.normal_gap = lin.area0 / lin.edge_length;
    c.normal_force = c.state == ContactState::Open ? 0.0 : std::max(0.0, -step.penalty * c.normal_gap);
    if (c.state == ContactState::Open) continue;
    const double limit = locked_shear_limit(s, c);
    const double shear = step.shear_penalty * lin.shear0;
    if (std::abs(shear) <= limit) continue;
    c.state = ContactState::Sliding;
    c.slip_direction = shear > 0.0 ? 1.0 : -1.0;
    c.bonded = false;
    const double offset = c.slip_direction * limit / step.shear_penalty;
    c.reference_ratio += (lin.shear0 - offset) / lin.edge_length;
    c.step_slip = 0.0;
    c.shear_offset = offset;
  }
  return ok;
}

}  // namespace ddafit
