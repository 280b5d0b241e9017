// Stage 3 of a step: Shi's open-close iteration. Assemble with the current contact
// states, solve, re-check the contacts, and repeat until no state changes (and the
// normal forces that drive friction have settled).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/options.hpp"
#include "forward/step/assemble.hpp"
#include "forward/step/check_contacts.hpp"
#include "forward/step/implicit_context.hpp"

namespace ddafit {

struct OpenCloseResult {
  bool converged = false;
  bool solver_failed = false;
  int iterations = 0;
  PointRef unsettled_contact;  // a point still changing state when the iteration gave up
  int unsettled = 0;           // contacts accepted while still changing on the last pass
  double cap_excess = 0.0;     // of the accepted iterate (ContactCheck::cap_excess)
  std::string reason;
};

// Relative change of the normal force of sliding contacts below which friction is
// considered settled (friction ~ N, and the slide acceleration is a small difference
// of gravity and friction, so N must be accurate to much better than 1 %).
constexpr double kNormalForceTolerance = 1e-3;

// Share of contacts that may still change state on the last pass of an accepted step.
constexpr double kUnsettledAllowance = 0.005;

// On ctx.contacts with ctx.equations; D of the last pass is left in ctx.equations.d.
OpenCloseResult open_close_iterate(ImplicitStepContext& ctx, const StepParameters& step);

}  // namespace ddafit
