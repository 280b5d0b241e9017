// Stage 4 of the implicit solver's step: the verdict on an attempt (Shi's control rules,
// docs/theory.md §8). Accept it; or try it again at the same length with a stiffer
// penalty, when a contact went deeper than allowed and the penalty may still rise; or redo
// it shorter, when the open-close iteration did not settle, a vertex moved further than
// allowed, the step created kinetic energy, or a stiffer penalty no longer helps.
#pragma once

#include <string>

#include "forward/step/assemble.hpp"
#include "forward/step/implicit_context.hpp"
#include "forward/step/open_close_iterate.hpp"

namespace ddafit {

enum class StepVerdict { Accept, Stiffer, Shorter };

struct StepJudgement {
  StepVerdict verdict = StepVerdict::Accept;
  double cut_factor = 1.0;  // Shorter: the next attempt's length over this one's
  std::string why;          // Shorter: the reason, for the diagnosis if the step cannot shrink
};

// Raises ctx.control's penalty (and counts it) when the verdict is Stiffer.
StepJudgement judge_step(ImplicitStepContext& ctx, const StepParameters& step, const OpenCloseResult& oc);

// "contact of blocks 'a' and 'b' at (x, y) (state, gap g m)", for diagnoses.
std::string describe_contact(const BlockSystem& system, const ContactSet& contacts, PointRef at);

}  // namespace ddafit
