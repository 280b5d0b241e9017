// The spread of a run: K realisations of one scene (forward/perturb.hpp; realisation 0 is
// the scene as given), summarised per measure point and quantity of kPointQuantities.
#pragma once

#include <string>
#include <vector>

#include "forward/run_summary.hpp"

namespace ddafit {

struct Spread {
  double mean = 0.0;
  double standard_deviation = 0.0;  // sample (n - 1); 0 for one member
  double low = 0.0, high = 0.0;     // range over the members
};

struct EnsemblePoint {
  std::string name;
  std::vector<Spread> quantities;  // in kPointQuantities order
};

struct EnsembleSummary {
  int members = 0;    // realisations run
  double jitter_ratio = 0.0;  // the nudge of the members (SimulationOptions::jitter_ratio)
  int completed = 0;  // of which completed; only these enter the statistics
  std::vector<EnsemblePoint> points;
  std::vector<std::string> failures;  // "realisation K: message" of each member that did not complete
};

// The statistics of the completed members' summaries (members[k] is realisation k).
EnsembleSummary summarise_ensemble(const std::vector<SimulationSummary>& members);

// A quantity's spread by name ("max_total_displacement"); null when the point or quantity
// is unknown.
const Spread* find_spread(const EnsembleSummary& ensemble, const std::string& point, const std::string& quantity);

}  // namespace ddafit
