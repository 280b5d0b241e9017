// method.levels: multi_fidelity (multi_fidelity.hpp): the correction, a line per
// observation through the fine runs' differences from the coarse ones, and the coarse
// evaluation it corrects. The steps that place the runs are fidelity_levels.cpp.
#include "inverse/multi_fidelity.hpp"

#include <algorithm>
#include <cmath>

namespace ddafit::inverse {

void fit_correction(const Study& study, FidelityCorrection& c) {
  const size_t m = study.observations.size();
  c.offset.assign(m, 0.0);
  c.slope.assign(m, 0.0);
  std::vector<const FidelityRun*> good;
  for (const FidelityRun& r : c.runs)
    if (!r.fine.failed && !r.coarse.failed) good.push_back(&r);
  if (good.empty()) return;
  double mean_p = 0.0;
  for (const FidelityRun* r : good) mean_p += r->value / good.size();
  double spp = 0.0;
  for (const FidelityRun* r : good) spp += (r->value - mean_p) * (r->value - mean_p);
  for (size_t k = 0; k < m; ++k) {
    double mean_d = 0.0, spd = 0.0;
    for (const FidelityRun* r : good) mean_d += (r->fine.simulated[k] - r->coarse.simulated[k]) / good.size();
    for (const FidelityRun* r : good)
      spd += (r->value - mean_p) * (r->fine.simulated[k] - r->coarse.simulated[k] - mean_d);
    // One distinct p (or one run): a constant offset; else the least-squares line.
    c.slope[k] = spp > 0.0 ? spd / spp : 0.0;
    c.offset[k] = mean_d - c.slope[k] * mean_p;
  }
  double sum = 0.0;
  long terms = 0;
  for (FidelityRun& r : c.runs) {
    r.predicted.assign(m, NAN);
    if (r.coarse.failed) continue;
    for (size_t k = 0; k < m; ++k) {
      r.predicted[k] = r.coarse.simulated[k] + c.offset[k] + c.slope[k] * r.value;
      if (r.fine.failed) continue;
      // In the chi^2's terms: a limit that holds at both counts 0 (a duration of 33 s against
      // a 45 s limit predicted as 37 s does not change the fit).
      const Observation& o = study.observations[k];
      const double e = observation_residual(o, r.fine.simulated[k], o.effective_sigma()) -
                       observation_residual(o, r.predicted[k], o.effective_sigma());
      sum += e * e;
      ++terms;
    }
  }
  c.rms_sigma = terms > 0 ? std::sqrt(sum / terms) : 0.0;
}

Evaluation corrected(const Study& study, const FidelityCorrection& c, const Evaluation& coarse) {
  Evaluation e = coarse;
  if (e.failed || c.parameter < 0) return e;
  const double p = e.values[c.parameter];
  e.chi2 = 0.0;
  for (size_t k = 0; k < study.observations.size(); ++k) {
    const Observation& o = study.observations[k];
    e.simulated[k] += c.offset[k] + c.slope[k] * p;
    e.residuals[k] = observation_residual(o, e.simulated[k], o.effective_sigma());
    e.chi2 += e.residuals[k] * e.residuals[k];
  }
  return e;
}

}  // namespace ddafit::inverse
