// Multi-fidelity back-analysis (method.levels: multi_fidelity): the coarse level (section I,
// seconds a run) is fitted and profiled as usual; a few runs of the fine level (section VII,
// minutes a run) measure how far the coarse model is off, observable by observable, and the
// profile is read off the corrected coarse model:
//
//   y_fine,k(x) ~ y_coarse,k(x) + a_k + b_k p        (p the profiled parameter)
//
// a_k, b_k by least squares over the fine runs (an "additive bias" correction, the simplest
// of the multi-fidelity surrogates; Kennedy & O'Hagan 2000 model the bias as a Gaussian
// process, here a line along the one profiled direction, which is all two or three fine runs
// can pin down). Where the bias is linear in p the corrected profile is the fine profile;
// where it is not, the fine runs' own misfit against the corrected model says by how much
// (FidelityCorrection::rms_sigma), and the report gives it.
#pragma once

#include <vector>

#include "inverse/objective.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

// One fine run and the coarse run at the same point.
struct FidelityRun {
  double value = 0.0;          // the profiled parameter
  Evaluation fine, coarse;     // the two levels' runs (others at the coarse best)
  std::vector<double> predicted;  // the corrected coarse model at this point, per observation
};

struct FidelityCorrection {
  bool used = false;
  int parameter = -1;        // the profiled parameter (p)
  int level_parameter = -1;  // the parameter with the two levels
  double coarse_level = 0.0, fine_level = 0.0;
  std::vector<double> offset, slope;  // a_k, b_k per observation (units of the observation, per unit of p)
  std::vector<FidelityRun> runs;      // in the order they ran
  // RMS over runs and observations of the fine run's residual minus the corrected model's
  // (observation_residual, in sigma_eff; (fine - corrected) / sigma_eff for an equality, 0
  // for a limit that holds at both): 0 where the bias is linear; with three runs and a line
  // through them, what the line leaves out plus the fine level's own scatter.
  double rms_sigma = 0.0;
  // The corrected model's chi^2 at the last fine run against the run's own (the check run
  // placed at the corrected optimum), when there is one.
  double check_predicted_chi2 = 0.0, check_chi2 = 0.0;
  bool checked = false;
};

// Least-squares a_k + b_k p through fine - coarse over the runs whose two levels completed
// (one run: b = 0). Fills offset, slope, each run's predicted values and rms_sigma.
void fit_correction(const Study& study, FidelityCorrection& c);

// A coarse evaluation with the correction added to its simulated values, re-scored
// (residuals, chi^2) with each observation's effective sigma. A failed run stays failed.
Evaluation corrected(const Study& study, const FidelityCorrection& c, const Evaluation& coarse);

}  // namespace ddafit::inverse
