#include "forward/analysis/ensemble.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace ddafit {

EnsembleSummary summarise_ensemble(const std::vector<SimulationSummary>& members) {
  EnsembleSummary e;
  e.members = static_cast<int>(members.size());
  std::vector<const SimulationSummary*> done;
  for (size_t k = 0; k < members.size(); ++k) {
    if (members[k].status == RunStatus::Completed) done.push_back(&members[k]);
    else e.failures.push_back("realisation " + std::to_string(k) + ": " + members[k].message);
  }
  e.completed = static_cast<int>(done.size());
  if (done.empty()) return e;
  constexpr size_t kQuantities = std::size(kPointQuantities);
  for (size_t p = 0; p < done.front()->points.size(); ++p) {
    EnsemblePoint point;
    point.name = done.front()->points[p].name;
    for (size_t q = 0; q < kQuantities; ++q) {
      std::vector<double> values;
      for (const SimulationSummary* s : done) values.push_back(kPointQuantities[q].get(s->points[p]));
      Spread spread;
      double sum = 0.0;
      for (double v : values) sum += v;
      spread.mean = sum / static_cast<double>(values.size());
      double squares = 0.0;
      for (double v : values) squares += (v - spread.mean) * (v - spread.mean);
      spread.standard_deviation =
          values.size() > 1 ? std::sqrt(squares / static_cast<double>(values.size() - 1)) : 0.0;
      spread.low = *std::min_element(values.begin(), values.end());
      spread.high = *std::max_element(values.begin(), values.end());
      point.quantities.push_back(spread);
    }
    e.points.push_back(point);
  }
  return e;
}

const Spread* find_spread(const EnsembleSummary& e, const std::string& point, const std::string& quantity) {
  for (const EnsemblePoint& p : e.points) {
    if (p.name != point) continue;
    for (size_t q = 0; q < std::size(kPointQuantities) && q < p.quantities.size(); ++q)
      if (quantity == kPointQuantities[q].name) return &p.quantities[q];
  }
  return nullptr;
}

}  // namespace ddafit
