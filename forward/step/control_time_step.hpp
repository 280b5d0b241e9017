// Stage 6: automatic time-step and penalty control (Shi's rules, field notes):
// a step is redone shorter when the open-close iteration does not settle or a vertex
// moves more than allowed, redone stiffer when a contact penetrates too deep, and the
// step grows back by a bounded factor while all is calm.
#pragma once

#include <string>

#include "forward/options.hpp"

namespace ddafit {

struct TimeStepControl {
  double max_step = 0.0;          // s, the scene's time.step
  double min_step = 0.0;          // s, below this the run fails
  double max_displacement = 0.0;  // m per step
  double max_penetration = 0.0;   // m
  double step = 0.0;              // s, the step the next attempt uses
  double base_penalty = 0.0;      // N/m, the scene's penalty, the floor the penalty relaxes to
  double penalty = 0.0;           // N/m, current normal penalty
  int penalty_raises = 0;         // raises within the current step
  bool cut_this_step = false;
};

TimeStepControl make_time_step_control(const SimulationOptions& options, double max_step,
                                       double half_model_size, double penalty);

// Each returns false when the run cannot continue (the step or the penalty is at its limit).
bool cut_step(TimeStepControl& control, double factor);
bool raise_penalty(TimeStepControl& control, const SimulationOptions& options);

// After an accepted step: grow the step again unless it was just cut, and let a raised
// penalty relax towards the scene's (as the step grows back when calm, a penalty
// raised for one hard impact should not stiffen the rest of the run).
void grow_step(TimeStepControl& control, const SimulationOptions& options);

}  // namespace ddafit
