#include "forward/step/control_time_step.hpp"

#include <algorithm>

namespace ddafit {

TimeStepControl make_time_step_control(const SimulationOptions& options, double max_step,
                                       double half_model_size, double penalty) {
  TimeStepControl c;
  c.max_step = max_step;
  c.min_step = options.min_step_ratio * max_step;
  c.max_displacement = options.max_displacement_ratio * half_model_size;
  c.max_penetration = options.max_penetration_ratio * half_model_size;
  c.step = max_step;
  c.penalty = penalty;
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
  c.cut_this_step = false;
}

}  // namespace ddafit
