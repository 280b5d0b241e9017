#include "forward/step/control_time_step.hpp"

#include <algorithm>

namespace ddafit {

// A raised penalty falls back by this factor per calm step (it rises by
// penalty_raise_factor, default 3, per redo).
constexpr double kPenaltyRelaxation = 1.2;

TimeStepControl make_time_step_control(const SimulationOptions& options, double max_step,
                                       double half_model_size, double max_move, double penalty,
                                       double heaviest_weight) {
  TimeStepControl c;
  c.max_step = max_step;
  c.min_step = options.min_step_ratio * max_step;
  c.max_displacement = max_move;
  c.max_penetration = options.max_penetration_ratio * half_model_size;
  c.contact_tolerance = options.contact_tolerance_ratio * c.max_displacement;
  if (heaviest_weight > 0.0 && penalty > 0.0)
    c.contact_tolerance = std::min(c.contact_tolerance, kRestingOverlapShare * heaviest_weight / penalty);
  c.step = max_step;
  c.penalty = c.base_penalty = penalty;
  return c;
}

bool cut_step(TimeStepControl& c, double factor) {
  c.step *= factor;
  c.cut_this_step = true;
  return c.step >= c.min_step;
}

bool raise_penalty(TimeStepControl& c, const SimulationOptions& options) {
  if (c.penalty_raises >= options.max_penalty_raises) return false;
  c.penalty *= options.penalty_raise_factor;
  ++c.penalty_raises;
  return true;
}

void grow_step(TimeStepControl& c, const SimulationOptions& options) {
  if (!c.cut_this_step) c.step = std::min(c.step * options.step_growth_factor, c.max_step);
  if (c.penalty_raises == 0) c.penalty = std::max(c.base_penalty, c.penalty / kPenaltyRelaxation);
  c.cut_this_step = false;
  c.penalty_raises = 0;
}

}  // namespace ddafit
