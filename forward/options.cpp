// The options' names and their check before a run (options.hpp), in the file's terms.
#include <cmath>
#include <string>

#include "forward/options.hpp"
#include "forward/value_checks.hpp"

namespace ddafit {

const char* to_string(Integrator integrator) {
  switch (integrator) {
    case Integrator::Implicit: return "implicit";
    case Integrator::Substep: return "substep";
    case Integrator::Auto: return "auto";
    case Integrator::Sled: return "sled";
  }
  return "?";
}

std::string validate_options(const SimulationOptions& o) {
  struct Check {
    const char* key;
    double value;
    bool ok;
    const char* rule;
  };
  const Check checks[] = {
      {"max_displacement_ratio", o.max_displacement_ratio,
       o.max_displacement_ratio > 0 && o.max_displacement_ratio <= 0.1,
       "must be in (0, 0.1]; typical 0.001-0.01"},
      {"penalty", o.penalty, non_negative(o.penalty),
       "must be >= 0 N/m (0 = automatic from penalty_factor)"},
      {"penalty_factor", o.penalty_factor, positive(o.penalty_factor),
       "must be > 0"},
      {"shear_penalty_ratio", o.shear_penalty_ratio,
       o.shear_penalty_ratio > 0 && o.shear_penalty_ratio <= 1, "must be in (0, 1]"},
      {"max_open_close_iterations", static_cast<double>(o.max_open_close_iterations),
       o.max_open_close_iterations >= 2, "must be >= 2"},
      {"step_cut_factor", o.step_cut_factor, o.step_cut_factor > 0 && o.step_cut_factor < 1,
       "must be in (0, 1)"},
      {"step_growth_factor", o.step_growth_factor,
       o.step_growth_factor >= 1 && std::isfinite(o.step_growth_factor),
       "must be >= 1; typical <= 1.3"},
      {"min_step_ratio", o.min_step_ratio, o.min_step_ratio > 0 && o.min_step_ratio < 1,
       "must be in (0, 1)"},
      {"max_penetration_ratio", o.max_penetration_ratio,
       positive(o.max_penetration_ratio), "must be > 0"},
      {"penalty_raise_factor", o.penalty_raise_factor,
       o.penalty_raise_factor > 1 && std::isfinite(o.penalty_raise_factor), "must be > 1"},
      {"max_penalty_raises", static_cast<double>(o.max_penalty_raises),
       o.max_penalty_raises >= 0, "must be >= 0"},
      {"settle_passes", static_cast<double>(o.settle_passes), o.settle_passes >= 0 && o.settle_passes <= 100,
       "must be in [0, 100]"},
      {"contact_tolerance_ratio", o.contact_tolerance_ratio,
       o.contact_tolerance_ratio >= 0 && o.contact_tolerance_ratio <= 0.1, "must be in [0, 0.1]"},
      {"max_pushout_speed", o.max_pushout_speed, positive(o.max_pushout_speed), "must be > 0 m/s"},
      {"contact_hertz", o.contact_hertz, o.contact_hertz >= 0 && o.contact_hertz <= 1e6,
       "must be in [0, 1e6] Hz (0 = automatic)"},
      {"contact_damping_ratio", o.contact_damping_ratio,
       o.contact_damping_ratio >= 0 && o.contact_damping_ratio <= 1e3, "must be in [0, 1000]"},
      {"sleep_time", o.sleep_time, o.sleep_time >= 0.0 && o.sleep_time <= 1e6, "must be in [0, 1e6] s (0 = never)"},
      {"sleep_speed", o.sleep_speed, o.sleep_speed >= 0.0 && o.sleep_speed <= 1e3,
       "must be in [0, 1000] m/s (0 = 1 % of rest_speed)"},
      {"contact_passes", static_cast<double>(o.contact_passes), o.contact_passes >= 1 && o.contact_passes <= 64,
       "must be a whole number in [1, 64]"},
      {"quiet_start_steps", static_cast<double>(o.quiet_start_steps),
       o.quiet_start_steps >= 0 && o.quiet_start_steps <= 10000, "must be a whole number in [0, 10000]"},
      {"deep_overlap_ratio", o.deep_overlap_ratio, o.deep_overlap_ratio >= 0.0 && o.deep_overlap_ratio <= 0.1,
       "must be in [0, 0.1] (0 = automatic)"},
      {"substeps", static_cast<double>(o.substeps), o.substeps >= 1 && o.substeps <= 1000,
       "must be in [1, 1000]"},
      {"search_distance_factor", o.search_distance_factor,
       o.search_distance_factor >= 1 && std::isfinite(o.search_distance_factor), "must be >= 1"},
  };
  for (const Check& c : checks)
    if (!c.ok)
      return std::string(c.key == std::string("substeps") ? "time." : "control.") + c.key + ": is " + shortest_text(c.value) +
             "; " + c.rule;
  return {};
}

}  // namespace ddafit
