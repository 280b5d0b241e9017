// Ranking hypotheses (inverse/hypotheses.hpp): the criteria's arithmetic and verdicts on
// made-up fits, the study file's `hypotheses:` key, and a twin experiment in which the
// observations come from one friction law and the ranking must not put another ahead of it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "inverse/forward_call.hpp"
#include "tests/twin_observations.hpp"
#include "inverse/hypotheses.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ddafit;
using namespace ddafit::inverse;

const std::string kScene = std::string(DDAFIT_CASES_DIR) + "/inverse/two_sliders.yaml";

fs::path fresh_dir(const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A fit with the given chi^2 and k continuous parameters, over n observations.
HypothesisFit made_up(const std::string& name, double chi2, int k, int n) {
  HypothesisFit f;
  f.name = name;
  for (int i = 0; i < k; ++i) f.study.parameters.push_back({"p" + std::to_string(i), "k", 0, 1, 0.5, 0.1, {}});
  f.study.observations.resize(static_cast<size_t>(n));
  f.summary.levels.resize(1);
  f.summary.best_level = 0;
  f.summary.levels[0].best.chi2 = chi2;
  return f;
}

TEST(HypothesisRanking, AicPenalisesParametersAndOrdersTheFits) {
  // AIC = chi2 + 2k, BIC = chi2 + k ln n (hypotheses.hpp); exact arithmetic.
  const HypothesisRanking r = rank_hypotheses({made_up("two", 3.0, 2, 4), made_up("one", 4.5, 1, 4)});
  ASSERT_EQ(r.fits.size(), 2u);
  EXPECT_EQ(r.fits[0].name, "one");  // 6.5 against 7.0
  EXPECT_DOUBLE_EQ(r.fits[0].aic, 6.5);
  EXPECT_DOUBLE_EQ(r.fits[1].aic, 7.0);
  EXPECT_DOUBLE_EQ(r.fits[1].bic, 3.0 + 2.0 * std::log(4.0));
  EXPECT_DOUBLE_EQ(r.fits[1].delta_aic, 0.5);
  // Within 2 of each other: no winner is named.
  EXPECT_EQ(r.tied.size(), 2u);
  EXPECT_NE(r.verdict.find("not distinguishable on these observations"), std::string::npos) << r.verdict;
}

TEST(HypothesisRanking, AClearWinnerIsNamedAndAFailedFitGoesLast) {
  HypothesisFit failed = made_up("broken", 0.0, 1, 4);
  failed.summary.levels[0].best.failed = true;
  const HypothesisRanking r = rank_hypotheses({failed, made_up("poor", 12.0, 2, 4), made_up("good", 1.0, 2, 4)});
  EXPECT_EQ(r.fits[0].name, "good");
  EXPECT_EQ(r.fits[1].name, "poor");
  EXPECT_TRUE(r.fits[2].failed);
  EXPECT_DOUBLE_EQ(r.fits[1].delta_aic, 11.0);
  ASSERT_EQ(r.tied.size(), 1u);
  EXPECT_NE(r.verdict.find("good explains these observations best"), std::string::npos) << r.verdict;
}

// The twin: two sliders (cases/inverse/two_sliders.yaml) whose basal clay follows the
// exponential law at 30 % degradation with d_c = 20 % of the block (long enough for the
// law's shape to show), observed with sigma 0.01 m and m/s.
fs::path hypotheses_study(const std::string& tag) {
  const SimulationResult truth = run_forward(io::read_scene(kScene, {{"interfaces.clay.degradation_percent", "30"},
                                                                     {"interfaces.clay.critical_distance_ratio", "0.2"},
                                                                     {"interfaces.clay.law", "exponential"}}));
  EXPECT_EQ(truth.summary.status, RunStatus::Completed) << truth.summary.message;
  const std::string obs = testing_twin::twin_observations(truth);
  const fs::path path = fresh_dir(tag) / "study.yaml";
  std::ofstream(path) << "scene: " << kScene << "\n"
                      << "settings: {interfaces.clay.critical_distance_ratio: 0.2}\n"
                      << "parameters:\n"
                      << "  - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 0, upper: 60,"
                      << " start: 10, resolution: 0.5}\n"
                      << "observations:\n"
                      << obs << "method: {optimizer: nlopt, algorithm: LN_BOBYQA, budget: 25}\n"
                      << "profile: {points: 5}\n"
                      << "hypotheses:\n"
                      << "  - {name: bilinear}\n"
                      << "  - {name: exponential, settings: {interfaces.clay.law: exponential}}\n"
                      << "  - name: velocity_weakening\n"
                      << "    settings: {interfaces.clay.law: velocity_weakening}\n"
                      << "    parameters:\n"
                      << "      - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 0,"
                      << " upper: 60, start: 10, resolution: 0.5}\n"
                      << "      - {name: weakening_velocity, key: interfaces.clay.weakening_velocity, lower: 0.05,"
                      << " upper: 2, start: 0.3, resolution: 0.01}\n";
  return path;
}

TEST(HypothesisRanking, TheLawThatMadeTheObservationsIsNotRankedBehindAnother) {
  const fs::path path = hypotheses_study("hypotheses_twin");
  const Study study = read_study(path.string());
  ASSERT_EQ(study.hypotheses.size(), 3u);
  EXPECT_EQ(study.hypotheses[2].parameters.size(), 2u);
  std::vector<HypothesisFit> fits;
  for (const Hypothesis& h : study.hypotheses) {
    HypothesisFit f;
    f.name = h.name;
    f.study = hypothesis_study(study, h);
    InversionOptions options;
    options.out_dir = (path.parent_path() / "hypotheses" / h.name).string();
    options.model_version = "test";
    f.summary = run_inversion(f.study, options);
    fits.push_back(std::move(f));
  }
  const HypothesisRanking r = rank_hypotheses(fits);
  // The truth's own law recovers it: chi2 well under the number of observations.
  const auto truth = std::find_if(r.fits.begin(), r.fits.end(), [](const HypothesisFit& f) { return f.name == "exponential"; });
  ASSERT_NE(truth, r.fits.end());
  EXPECT_LT(truth->chi2, 1.0);
  EXPECT_EQ(truth->fitted, 1);
  // First, or tied with the first (Delta AIC < 2).
  EXPECT_TRUE(r.fits.front().name == "exponential" ||
              std::find(r.tied.begin(), r.tied.end(), "exponential") != r.tied.end())
      << r.verdict;
  write_ranking(path.parent_path().string(), r);
  std::ifstream md(path.parent_path() / "ranking.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(r.verdict), std::string::npos);
  for (const HypothesisFit& f : r.fits)
    std::printf("[hypothesis] %-20s chi2 %.4g  k %d  AIC %.3f  dAIC %.3f\n", f.name.c_str(), f.chi2, f.fitted, f.aic,
                f.delta_aic);
  std::printf("[hypothesis] %s\n", r.verdict.c_str());
}

TEST(HypothesisRanking, StudyFileRefusesAHypothesisAlone) {
  const fs::path path = fresh_dir("hypotheses_bad") / "study.yaml";
  const std::string head = "scene: " + kScene + "\nparameters:\n  - {name: d, key: interfaces.clay.degradation_percent, "
                           "lower: 0, upper: 60, start: 10, resolution: 0.5}\nobservations:\n  - {point: A, quantity: "
                           "max_total_displacement, value: 1, sigma: 0.1}\n";
  const auto fails_with = [&](const std::string& tail, const std::string& key, const std::string& words) {
    std::ofstream(path) << head << tail;
    try {
      read_study(path.string());
    } catch (const StudyError& e) {
      const std::string m = e.what();
      return m.find(key) != std::string::npos && m.find(words) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(fails_with("hypotheses:\n  - {name: one}\n", "hypotheses", "at least two"));
  EXPECT_TRUE(fails_with("hypotheses:\n  - {name: a}\n  - {name: a}\n", "hypotheses[1].name", "used twice"));
  EXPECT_TRUE(fails_with("hypotheses:\n  - {name: a}\n  - {name: 'b/c'}\n", "hypotheses[1].name", "names a folder"));
  EXPECT_TRUE(fails_with("hypotheses:\n  - {name: a}\n  - {name: b, law: exponential}\n", "hypotheses[1].law",
                         "unknown key"));
}

}  // namespace
