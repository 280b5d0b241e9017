#include "forward/step/judge_step.hpp"

#include <algorithm>
#include <sstream>

#include "forward/step/update_blocks.hpp"

namespace ddafit {

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
  PointRef deepest;
  // Half the search distance: deeper, a contact is close to being lost altogether.
  const double depth =
      max_penetration(ctx.contacts, step, control.max_penetration, 0.5 * ctx.detection.settings.margin, &deepest);
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
