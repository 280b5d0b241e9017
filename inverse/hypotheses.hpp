// Competing explanations of one set of observations, fitted each on its own and ranked
// (issue "Which weakening explains Vajont?"): a study's `hypotheses:` each bring their scene
// settings (a friction law and its fixed numbers) and, if they wish, their own parameters.
//
// Ranked by Akaike's information criterion on the fit's chi^2 (for Gaussian errors
// -2 ln L = chi^2 + const): AIC = chi2_min + 2 k, BIC = chi2_min + k ln n, with k the fitted
// continuous parameters and n the observations. Two hypotheses within Delta AIC < 2 of the
// best are "not distinguishable on these observations" (Burnham & Anderson 2002, §2.6: less
// than 2 is substantial support for both); the report then names no winner.
#pragma once

#include <string>
#include <vector>

#include "inverse/inversion.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

// The study as hypothesis h fits it: the study's settings then h's, h's parameters if it
// has them (else the study's), and no hypotheses of its own.
Study hypothesis_study(const Study& study, const Hypothesis& h);

// read_study(), then each hypothesis (or the study itself, without hypotheses) checked
// against the scene with its own settings (its law may be what makes a parameter such as
// weakening_velocity settable). Throws StudyError. For `ddafit invert` and ddafit.invert().
Study read_checked_study(const std::string& path);

struct HypothesisFit {
  std::string name;
  Study study;               // as fitted (hypothesis_study)
  InversionSummary summary;
  double chi2 = 0.0;         // at the reported level's best point
  int fitted = 0;            // k: continuous parameters fitted
  int observations = 0;      // n
  double aic = 0.0, bic = 0.0;
  double delta_aic = 0.0, delta_bic = 0.0;  // against the best of each
  bool failed = false;       // every run failed: ranked last, no criterion
};

struct HypothesisRanking {
  std::vector<HypothesisFit> fits;  // best AIC first; failed fits last
  std::vector<std::string> tied;    // the hypotheses within Delta AIC < 2 of the best (the best included)
  std::string verdict;              // one sentence
};

// Fills each fit's criteria and orders them. The fits' names, studies and summaries are given.
HypothesisRanking rank_hypotheses(std::vector<HypothesisFit> fits);

// ranking.md, ranking.json and ranking.png (the best run of each on one velocity-distance
// chart beside the observations' bands) in `dir`. Returns notes (a chart that could not be
// drawn); throws std::runtime_error if a file cannot be written.
std::vector<std::string> write_ranking(const std::string& dir, const HypothesisRanking& ranking);

}  // namespace ddafit::inverse
