// The twin experiments' observations (test_inverse.cpp, test_hypotheses.cpp): every measure
// point's largest displacement and peak speed of a run at the truth, as study-file lines
// with sigma 0.01 m and m/s.
#pragma once

#include <string>

#include "forward/run_summary.hpp"
#include "inverse/forward_call.hpp"

namespace ddafit::testing_twin {

inline std::string twin_observations(const SimulationResult& truth) {
  std::string obs;
  for (const PointSummary& p : truth.summary.points)
    obs += "  - {point: " + p.name + ", quantity: max_total_displacement, value: " +
           inverse::exact_text(p.max_total_displacement) + ", sigma: 0.01}\n" + "  - {point: " + p.name +
           ", quantity: peak_total_velocity, value: " + inverse::exact_text(p.peak_total_velocity) + ", sigma: 0.01}\n";
  return obs;
}

}  // namespace ddafit::testing_twin
