#include "forward/step/judge_step.hpp"

#include <algorithm>
#include <sstream>

#include "forward/common/displace_block.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/step/update_blocks.hpp"
#include "forward/water/hydrostatic.hpp"

namespace ddafit {
namespace {

// A step may add at most this share of its kinetic energy (plus the audit's floor) beyond
// gravity's work before it is redone shorter.
constexpr double kStepEnergyTolerance = 0.1;

// A step accepted at its pass limit with capped locks (check_contacts.cpp) whose shear still
// exceeds the Coulomb cap by more than this share of the step's largest contact force is
// redone shorter (model revision 2026-12-02.4): such a step hands the blocks friction that
// Coulomb's law does not allow. A row of tall blocks struck sideways at 45 deg, mirrored,
// tipped on its front corner with frozen locks at up to ten times their cap (their normal
// forces fell twentyfold in the last pass), and the row and its striker leapt off the floor:
// the floor took 45 % of the impact's momentum beyond its friction (tests/test_impact_rows.cpp).
constexpr double kCapExcessTolerance = 0.1;

// Largest displacement of any vertex over the step for the solved unknowns d.
double max_vertex_displacement(const BlockSystem& s, const Eigen::VectorXd& d) {
  double largest = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (s.blocks[b].unknown >= 0)
      largest = std::max(largest, block_displacement(s, b, d.segment<6>(6 * s.blocks[b].unknown)));
  return largest;
}

struct DeepestPoint {
  double depth = 0.0;  // m, > 0
  PointRef which;
};

// Deepest penetration (> 0) among closed contacts that the step made deeper, and which
// contact it is. Depth counts from where the spring is unloaded (spring_reference), so
// a deep contact being pushed out is judged on what the step adds. A contact deeper than
// half the search distance in all (close to being lost altogether) reads as at least as
// deep as the step's penetration limit: a penalty too soft would otherwise let a block
// sink a little further every step, each step mending nothing.
DeepestPoint max_penetration(const ImplicitStepContext& ctx, const StepParameters& step) {
  const ContactSet& contacts = ctx.contacts;
  const double limit = ctx.control.max_penetration, hard_limit = 0.5 * ctx.detection.settings.margin;
  DeepestPoint deepest;
  for (int k = 0; k < static_cast<int>(contacts.manifolds.size()); ++k) {
    const ContactManifold& m = contacts.manifolds[k];
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      const SpringState& c = p.spring;
      // Only points this step drove deeper: one found already deep (a corner that came
      // round a corner) cannot be mended by a stiffer spring within the step, only pushed
      // back out over the next steps.
      const double depth = std::max(spring_reference(p, step) - c.normal_gap, -c.normal_gap - (hard_limit - limit));
      if (c.state != ContactState::Open && c.normal_gap < p.separation && depth > deepest.depth)
        deepest = {depth, {k, q}};
    }
  }
  return deepest;
}

// Kinetic energy the attempt creates, J/m: its rise over the step less the work of the
// loads the step applied (assemble.cpp: gravity less the ground's acceleration on the
// centroid, and the water's force and moment half a step ahead) over the blocks' rigid-body
// moves. The kinetic energy is 1/2 rho V^T M V with the block's whole mass matrix, as in the
// run's energy audit (forward/common/energy_check.hpp; model revision 2026-12-06.17). Taken
// as 1/2 m v^2 + 1/2 I w^2, a 1 cm plate squeezed under a dropped block, whose shear rate
// moves its faces as its rotation does, read as creating energy in step after step: 316
// steps were cut, down to 3e-8 s, where 9 are now (tests/test_thin_plate.cpp). The velocities
// are the step's own update (update_blocks.hpp, step_velocity: v1 = 2 d / dt - v0 unless the step stopped the block
// impulsively). `scale` returns the kinetic energy before the step plus the audit's floor,
// 1e-4 x weight x H, against which the gain is judged.
double created_energy(const BlockSystem& s, const Eigen::VectorXd& d, const StepParameters& step, double* scale) {
  double created = 0.0, before = 0.0;
  const double dt = step.time_step, g = step.gravity.norm();
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.unknown < 0) continue;
    const Vec6 db = d.segment<6>(6 * block.unknown);
    double work = s.mass(b) * (step.gravity - step.ground_acceleration).dot(db.head<2>());
    if (s.water.present()) work += water_load(s, b, g, 0.5 * dt * block.velocity.head<3>()).head<3>().dot(db.head<3>());
    const double kinetic = block_kinetic_energy(s, b, block.velocity);
    before += kinetic;
    created += block_kinetic_energy(s, b, step_velocity(block, db, dt, g)) - kinetic - work;
  }
  *scale = before + energy_floor(s, step.gravity);
  return created;
}

}  // namespace


std::string describe_contact(const BlockSystem& s, const ContactSet& contacts, PointRef at) {
  const ContactManifold& m = contacts.manifolds[at.manifold];
  const ContactPoint& p = m.points[at.point];
  std::ostringstream out;
  out << "contact of blocks '" << s.block_names[m.block_a] << "' and '" << s.block_names[m.block_b] << "' at ("
      << p.anchor.x() << ", " << p.anchor.y() << ") (" << to_string(p.spring.state) << ", gap " << p.spring.normal_gap
      << " m)";
  return out.str();
}

StepJudgement judge_step(ImplicitStepContext& ctx, const StepParameters& step, const OpenCloseResult& oc) {
  TimeStepControl& control = ctx.control;
  StepJudgement shorter{StepVerdict::Shorter, ctx.options.step_cut_factor, {}};
  if (!oc.converged) {
    shorter.why = oc.reason;
    if (oc.unsettled_contact.manifold >= 0)
      shorter.why += " at the " + describe_contact(ctx.system, ctx.contacts, oc.unsettled_contact);
    return shorter;
  }
  if (const double moved = max_vertex_displacement(ctx.system, ctx.equations.d); moved > control.max_displacement) {
    shorter.why = "a vertex moved " + std::to_string(moved) + " m in one step (limit " +
                  std::to_string(control.max_displacement) + " m)";
    shorter.cut_factor = std::clamp(0.8 * control.max_displacement / moved, 0.1, 0.9);
    return shorter;
  }
  // A step whose contacts hand the blocks more kinetic energy than gravity gave them (a
  // corner that meets a bank at 20 m/s mid-step, its spring loaded over the whole step) is
  // redone shorter while it can shrink a hundredfold; the run's energy audit judges what
  // is left. Before: the block sliding at 20 m/s into a 55-65 deg bank at 10 ms left the
  // step at 26.5 m/s and the run stopped (tests/test_valley_corner.cpp).
  // The same hundredfold room for a step whose frozen locks end past their Coulomb cap
  // (kCapExcessTolerance): a step that cannot shrink further is accepted, never failed.
  if (step.time_step > 100.0 * control.min_step) {
    double scale = 0.0;
    if (const double created = created_energy(ctx.system, ctx.equations.d, step, &scale);
        created > kStepEnergyTolerance * scale) {
      shorter.why = "the step created " + std::to_string(created) + " J/m of kinetic energy";
      return shorter;
    }
    if (oc.cap_excess > kCapExcessTolerance) {
      shorter.why = "a locked contact carried " + std::to_string(oc.cap_excess) +
                    " of the largest contact force beyond its Coulomb cap";
      return shorter;
    }
  }
  const auto [depth, deepest] = max_penetration(ctx, step);
  if (depth <= control.max_penetration) return {};
  const std::string where = describe_contact(ctx.system, ctx.contacts, deepest);
  if (raise_penalty(control, ctx.options)) {
    ++ctx.run.penalty_raises;
    return {StepVerdict::Stiffer, 1.0, {}};
  }
  // A stiffer spring did not help: a corner running into a corner is caught earlier by a
  // shorter step. Only when the step can no longer shrink does the run stop.
  shorter.why = "penetration " + std::to_string(depth) + " m at the " + where + " stays above the limit after " +
                std::to_string(control.penalty_raises) + " penalty raises in this step";
  control.penalty_raises = 0;
  return shorter;
}

}  // namespace ddafit
