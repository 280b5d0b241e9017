// The back-analysis library: twin experiments (observations made by a forward run at
// known parameters must be recovered by NLopt and by Ceres), the evaluation cache, and
// the bounding friction of the profile.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "forward/io/scene_reader.hpp"
#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "tests/twin_observations.hpp"
#include "inverse/inversion.hpp"
#include "inverse/objective.hpp"
#include "inverse/report.hpp"
#include "inverse/study.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ddafit;
using namespace ddafit::inverse;

const std::string kScene = std::string(DDAFIT_CASES_DIR) + "/inverse/two_sliders.yaml";

// The truth of the twin experiments, and the resolutions the study gives.
constexpr double kTrueDegradation = 30.0;  // % on clay (slider A)
constexpr double kTrueRoughness = 3.0;     // deg on joint (slider B)
constexpr double kDegradationResolution = 0.5;
constexpr double kRoughnessResolution = 0.1;

fs::path fresh_dir(const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A study over the two sliders whose observations are a forward run at the truth. The
// truth's scene is the file read with its values written into the text (the CLI's --set),
// the study's runs set them as numbers on a scene read once: a study that recovers the
// truth also shows the two paths agree.
fs::path twin_study(const std::string& tag, const std::string& method, int profile_points) {
  const SimulationResult truth =
      run_forward(io::read_scene(kScene, {{"interfaces.clay.degradation_percent", exact_text(kTrueDegradation)},
                                          {"interfaces.joint.roughness_angle", exact_text(kTrueRoughness)}}));
  EXPECT_EQ(truth.summary.status, RunStatus::Completed) << truth.summary.message;
  const std::string obs = testing_twin::twin_observations(truth);
  const fs::path path = fresh_dir(tag) / "study.yaml";
  std::ofstream(path) << "scene: " << kScene << "\n"
                      << "parameters:\n"
                      << "  - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 0, upper: 60,"
                      << " start: 10, resolution: " << kDegradationResolution << "}\n"
                      << "  - {name: joint_roughness, key: interfaces.joint.roughness_angle, lower: 0, upper: 12,"
                      << " start: 7, resolution: " << kRoughnessResolution << "}\n"
                      << "observations:\n"
                      << obs << "method: " << method << "\n"
                      << "profile: {points: " << profile_points << "}\n";
  return path;
}

struct TwinRun {
  InversionSummary summary;
  double seconds = 0.0;
};

TwinRun invert(const fs::path& study_path, const std::string& out_tag) {
  const Study study = read_study(study_path.string());
  InversionOptions options;
  options.out_dir = fresh_dir(out_tag).string();
  options.model_version = "test";
  const auto t0 = std::chrono::steady_clock::now();
  TwinRun r;
  r.summary = run_inversion(study, options);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// Recovery tolerance: both methods stop once a step is below half a resolution (the
// default step_tolerance), and with noise-free twin data the minimum is at the truth, so
// the last point is within about one resolution of it; two resolutions leave room for
// the adaptive time step making chi^2 slightly rough at the sub-resolution scale.
void expect_recovered(const TwinRun& r, const char* method) {
  ASSERT_EQ(r.summary.levels.size(), 1u);
  const LevelFit& level = r.summary.levels.front();
  ASSERT_FALSE(level.best.failed) << level.best.message;
  EXPECT_NEAR(level.best.values[0], kTrueDegradation, 2 * kDegradationResolution) << method;
  EXPECT_NEAR(level.best.values[1], kTrueRoughness, 2 * kRoughnessResolution) << method;
  std::printf("[twin %s] degradation %.4f (true %.1f), roughness %.4f (true %.1f), chi2 %.3g, %ld runs, %.2f s, %s\n",
              method, level.best.values[0], kTrueDegradation, level.best.values[1], kTrueRoughness, level.best.chi2,
              r.summary.run, r.seconds, level.fit.stop_reason.c_str());
}

TEST(InverseTwin, NloptBobyqaRecoversBothDegradations) {
  const TwinRun r = invert(twin_study("twin_nlopt", "{optimizer: nlopt, algorithm: LN_BOBYQA, budget: 80}", 0),
                           "twin_nlopt/out");
  expect_recovered(r, "nlopt");
  // BOBYQA converges on its own rules long before the budget on this smooth problem.
  EXPECT_TRUE(r.summary.levels.front().fit.converged) << r.summary.levels.front().fit.stop_reason;
}

TEST(InverseTwin, CeresLevenbergMarquardtRecoversBothDegradations) {
  const TwinRun r = invert(twin_study("twin_ceres", "{optimizer: ceres, budget: 80}", 0), "twin_ceres/out");
  expect_recovered(r, "ceres");
  EXPECT_TRUE(r.summary.levels.front().fit.converged) << r.summary.levels.front().fit.stop_reason;
}

TEST(InverseTwin, NloptSubplexRecoversBothDegradations) {
  const TwinRun r = invert(twin_study("twin_sbplx", "{optimizer: nlopt, algorithm: LN_SBPLX, budget: 150}", 0),
                           "twin_sbplx/out");
  expect_recovered(r, "sbplx");
}

TEST(InverseTwin, DirectFindsTheBasinWithinItsBudget) {
  // DIRECT trisects the box: 150 evaluations leave boxes of about 1/27-1/81 of each range
  // around the best point, so the tolerance is a twentieth of the range (3 % and 0.6 deg),
  // coarser than a local method's by design.
  const TwinRun r = invert(twin_study("twin_direct", "{optimizer: nlopt, algorithm: GN_DIRECT_L, budget: 150}", 0),
                           "twin_direct/out");
  const LevelFit& level = r.summary.levels.front();
  EXPECT_NEAR(level.best.values[0], kTrueDegradation, 60.0 / 20);
  EXPECT_NEAR(level.best.values[1], kTrueRoughness, 12.0 / 20);
  // The budget caps the fit's objective calls (the covariance then adds up to one run per
  // parameter for its Jacobian).
  EXPECT_LE(r.summary.levels.front().fit.evaluations, 150);
}

TEST(InverseTwin, BoundingFrictionBracketsTheTruthAndAgreesWithTheCovariance) {
  const TwinRun r = invert(twin_study("twin_profile", "{optimizer: nlopt, budget: 80}", 11), "twin_profile/out");
  const BoundingFriction& f = r.summary.friction;
  ASSERT_TRUE(f.available) << f.why_not;
  EXPECT_DOUBLE_EQ(f.peak_angle, 25.0);  // clay's friction_angle in two_sliders.yaml
  const double mu_true = std::tan(25.0 * (1.0 - kTrueDegradation / 100.0) * M_PI / 180.0);
  // Noise-free data: the truth is the minimum, so it lies inside the Delta chi2 <= 1 range
  // (the bisection stops at one resolution, hence the one-resolution allowance).
  EXPECT_LE(f.delta1.low, kTrueDegradation + kDegradationResolution);
  EXPECT_GE(f.delta1.high, kTrueDegradation - kDegradationResolution);
  EXPECT_LE(f.delta4.mu_low, mu_true + 1e-3);
  EXPECT_GE(f.delta4.mu_high, mu_true - 1e-3);
  EXPECT_LT(f.delta4.mu_low, f.delta1.mu_low);  // Delta chi2 <= 4 is the wider range
  EXPECT_FALSE(f.delta4.low_at_bound || f.delta4.high_at_bound);
  // The two sliders are independent and nearly linear over a few resolutions, so the
  // covariance's standard deviation and the profile's Delta chi2 <= 1 half-width measure
  // the same thing; 25 % allows for the residual curvature across a one-resolution bracket.
  const CovarianceReport& c = r.summary.covariance;
  ASSERT_TRUE(c.computed);
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();  // 4 values for 2 parameters, inside bounds
  const double half_width = 0.5 * (f.delta1.high - f.delta1.low);
  EXPECT_NEAR(c.standard_deviation[0], half_width, 0.25 * half_width);
}

TEST(InverseProfile, AFailedRunNeitherEndsNorCutsTheRange) {
  // chi^2 = (x - 50)^2 / 25 on a grid of 1: Delta chi^2 <= 4 is exactly [40, 60]. A failed
  // run at 57 (the misfit a failure is counted as) must not end the range there: it says
  // nothing about the fit (the Vajont profile lost 58-60 % that way). Exact to round-off,
  // since sqrt(Delta chi^2) is linear in x and the interpolation is in sqrt(Delta).
  std::vector<ProfilePoint> profile;
  for (int x = 30; x <= 70; ++x) {
    ProfilePoint p;
    p.value = x;
    p.chi2 = (x - 50.0) * (x - 50.0) / 25.0;
    if (x == 57) {
      p.chi2 = kFailedMisfit;
      p.failed = true;
    }
    profile.push_back(p);
  }
  const ProfileRange r4 = profile_range(profile, 4.0);
  EXPECT_NEAR(r4.low, 40.0, 1e-9);
  EXPECT_NEAR(r4.high, 60.0, 1e-9);
  const ProfileRange r1 = profile_range(profile, 1.0);
  EXPECT_NEAR(r1.high, 55.0, 1e-9);
  EXPECT_FALSE(r4.high_at_bound);
}

TEST(InverseCovariance, WarnsWhenTheDataCannotConstrainTheParameters) {
  // One observation of slider A for two parameters: the joint roughness (slider B) moves no
  // residual, so there are no degrees of freedom and J has a zero column.
  const fs::path dir = fresh_dir("cov_warn");
  std::ofstream(dir / "study.yaml")
      << "scene: " << kScene << "\nparameters:\n"
      << "  - {name: deg, key: interfaces.clay.degradation_percent, lower: 0, upper: 60, start: 20, resolution: 0.5}\n"
      << "  - {name: rough, key: interfaces.joint.roughness_angle, lower: 0, upper: 12, start: 7, resolution: 0.1}\n"
      << "observations:\n  - {point: A, quantity: max_total_displacement, value: 2.6943, sigma: 0.01}\n"
      << "method: {budget: 40}\nprofile: {points: 0}\n";
  const TwinRun r = invert(dir / "study.yaml", "cov_warn/out");
  const CovarianceReport& c = r.summary.covariance;
  const auto mentions = [&](const std::string& text) {
    for (const std::string& w : c.warnings)
      if (w.find(text) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(mentions("no degrees of freedom"));
  EXPECT_TRUE(mentions("rough changes no residual"));
  EXPECT_TRUE(mentions("rank deficient"));
  EXPECT_FALSE(c.computed);  // a pseudo-inverse would look like an answer: none is given
}

// The degradation percent a study parameter gave an interface of the scene (NaN if none).
double degradation_of(const Scene& scene, const std::string& interface) {
  for (const Interface& f : scene.interfaces)
    if (f.name == interface && f.degradation_percent) return *f.degradation_percent;
  return NAN;
}

// A forward model that counts its runs and fails above 45 % degradation.
struct CountingForward {
  int* calls;
  SimulationResult operator()(const Scene& scene) const {
    ++*calls;
    if (degradation_of(scene, "clay") > 45.0) {
      SimulationResult failed;
      failed.summary.status = RunStatus::Failed;
      failed.summary.message = "test: step cut below the minimum";
      return failed;
    }
    return run_forward(scene);
  }
};

TEST(InverseObjective, FailedRunsAreValuesAndNoPointRunsTwice) {
  const Study study = read_study(twin_study("objective", "{optimizer: nlopt, algorithm: GN_DIRECT_L, budget: 60}", 11).string());
  InversionOptions options;
  options.out_dir = fresh_dir("objective/out").string();
  options.model_version = "test";
  int calls = 0;
  const InversionSummary s = run_inversion(study, options, CountingForward{&calls});
  // Every forward call is one distinct point (DIRECT and the profile revisit points; the
  // profile's scan includes the fit's points); none came from an earlier process.
  EXPECT_EQ(calls, s.run + s.history_reruns);
  EXPECT_EQ(s.run, s.evaluations);
  bool saw_failure = false;
  for (const std::string& note : s.notes) saw_failure = saw_failure || note.find("test: step cut") != std::string::npos;
  EXPECT_TRUE(saw_failure) << "DIRECT samples p > 45 and the failure is logged";
  const BoundingFriction& f = s.friction;
  for (const ProfilePoint& p : f.profile) EXPECT_EQ(p.failed, p.value > 45.0) << p.value;
  EXPECT_FALSE(s.levels.front().best.failed);
}

// A forward model that records the scene of every run.
struct RecordingForward {
  std::vector<Scene>* runs;
  SimulationResult operator()(const Scene& scene) const {
    runs->push_back(scene);
    return run_forward(scene);
  }
};

double roughness_of(const Scene& scene, const std::string& interface) {
  for (const Interface& f : scene.interfaces)
    if (f.name == interface) return f.roughness_angle;
  return NAN;
}

TEST(InverseLevels, CoarseToFineStartsEachLevelAtTheLastBestAndReportsTheFinest) {
  // The twin study with the time step as its levels, coarse (2 ms) then fine (the truth's
  // 1 ms): under method.levels coarse_to_fine the fine level's first run is exactly the
  // coarse level's best point, it takes at most fine_budget runs, and it is the level
  // reported. Recovery as in the twin tests (two resolutions).
  const fs::path path = twin_study("c2f", "{budget: 30, levels: coarse_to_fine, fine_budget: 12}", 0);
  std::string text;
  {
    std::ifstream in(path);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  text.replace(text.find("parameters:\n"), 12, "parameters:\n  - {name: step, key: time.step, levels: [0.002, 0.001]}\n");
  std::ofstream(path) << text;
  const Study study = read_study(path.string());
  ASSERT_TRUE(study.method.coarse_to_fine);
  InversionOptions options;
  options.out_dir = fresh_dir("c2f/out").string();
  options.model_version = "test";
  std::vector<Scene> runs;
  const InversionSummary s = run_inversion(study, options, RecordingForward{&runs});
  ASSERT_EQ(s.levels.size(), 2u);
  EXPECT_EQ(s.best_level, 1) << "coarse to fine reports the finest (last) level";
  const LevelFit& coarse = s.levels[0];
  const LevelFit& fine = s.levels[1];
  ASSERT_FALSE(coarse.best.failed);
  EXPECT_LE(fine.fit.evaluations, 12);
  const auto first_fine =
      std::find_if(runs.begin(), runs.end(), [](const Scene& s) { return s.max_step == 0.001; });
  ASSERT_NE(first_fine, runs.end());
  EXPECT_EQ(degradation_of(*first_fine, "clay"), coarse.best.values[1]);
  EXPECT_EQ(roughness_of(*first_fine, "joint"), coarse.best.values[2]);
  EXPECT_NEAR(fine.best.values[1], kTrueDegradation, 2 * kDegradationResolution);
  EXPECT_NEAR(fine.best.values[2], kTrueRoughness, 2 * kRoughnessResolution);
}

TEST(InverseLevels, CoarseToFineNeedsExactlyOneLeveledParameter) {
  const fs::path path = twin_study("c2f_bad", "{levels: coarse_to_fine}", 0);
  try {
    read_study(path.string());
    FAIL() << "a study without levels was accepted for coarse_to_fine";
  } catch (const StudyError& e) {
    EXPECT_NE(std::string(e.what()).find("method.levels"), std::string::npos) << e.what();
  }
}

TEST(InverseCache, StoresSummariesBitExactlyAndKeysOnExactValues) {
  const fs::path dir = fresh_dir("cache_exact");
  Study study;
  study.parameters.push_back({"p", "interfaces.clay.degradation_percent", 0, 1, 0.5, 0.1, {}});
  const double x = 0.1 + 0.2;  // 0.30000000000000004: not the double nearest 0.3
  EXPECT_NE(point_key(study, {x}), point_key(study, {0.3}));
  EXPECT_NE(point_key(study, {x}), point_key(study, {std::nextafter(x, 1.0)}));
  SimulationResult run;
  run.summary.points.push_back({"A", 1.0 / 3.0, M_PI, std::nextafter(2.0, 3.0), 1e-310, 45.000000000000007, true});
  run.history.push_back({0.5, 0, Vec2(1.0 / 7.0, 2.0), Vec2(3.0, -1.0 / 9.0), Vec2(0.1, 0.2)});
  // The ground surface a deposit observation reads: a resumed study once scored every cached
  // run as failed because the cache dropped it.
  run.summary.final_surface = {Vec2(450.0, 1.0 / 3.0), Vec2(452.5, M_PI * 200.0)};
  {
    EvaluationCache cache((dir / "c.sqlite").string(), "v1", "hash");
    cache.store(point_key(study, {x}), run, 1.5, true);
  }
  EvaluationCache reopened((dir / "c.sqlite").string(), "v1", "hash");
  const auto hit = reopened.find(point_key(study, {x}));
  ASSERT_TRUE(hit.has_value());
  const PointSummary& a = run.summary.points[0];
  const PointSummary& b = hit->result.summary.points[0];
  EXPECT_EQ(a.max_lateral_displacement, b.max_lateral_displacement);  // exact: a resume must replay identically
  EXPECT_EQ(a.max_total_displacement, b.max_total_displacement);
  EXPECT_EQ(a.peak_lateral_velocity, b.peak_lateral_velocity);
  EXPECT_EQ(a.peak_total_velocity, b.peak_total_velocity);
  EXPECT_EQ(a.duration, b.duration);
  EXPECT_EQ(a.stopped, b.stopped);
  EXPECT_EQ(hit->result.summary.final_surface, run.summary.final_surface);
  ASSERT_EQ(hit->result.history.size(), 1u);
  EXPECT_EQ(hit->result.history[0].position.x(), 1.0 / 7.0);
  EXPECT_FALSE(reopened.find(point_key(study, {0.3})).has_value());
  // Another model version or scene never sees the row.
  EXPECT_FALSE(EvaluationCache((dir / "c.sqlite").string(), "v2", "hash").find(point_key(study, {x})).has_value());
  EXPECT_FALSE(EvaluationCache((dir / "c.sqlite").string(), "v1", "other").find(point_key(study, {x})).has_value());
}

}  // namespace

namespace {

// One parameter and one observation of the twin: A's largest displacement against the
// basal degradation, at the truth (30 %). Near the truth the response is close to linear
// (chi2 quadratic), so adding a model_sigma s_m to sigma widens the Delta chi2 range by
// sqrt(sigma^2 + s_m^2) / sigma.
fs::path one_observation_study(const std::string& tag, const std::string& model_sigma) {
  const SimulationResult truth =
      run_forward(io::read_scene(kScene, {{"interfaces.clay.degradation_percent", exact_text(kTrueDegradation)},
                                          {"interfaces.joint.roughness_angle", exact_text(kTrueRoughness)}}));
  const fs::path path = fresh_dir(tag) / "study.yaml";
  std::ofstream(path) << "scene: " << kScene << "\n"
                      << "settings: {interfaces.joint.roughness_angle: " << kTrueRoughness << "}\n"
                      << "parameters:\n"
                      << "  - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 20, upper: 40,"
                      << " start: 28, resolution: 0.01}\n"
                      << "observations:\n"
                      << "  - {point: A, quantity: max_total_displacement, value: "
                      << exact_text(truth.summary.points[0].max_total_displacement) << ", sigma: 0.01"
                      << (model_sigma.empty() ? "" : ", model_sigma: " + model_sigma) << "}\n"
                      << "method: {optimizer: nlopt, algorithm: LN_BOBYQA, budget: 30}\n"
                      << "profile: {points: 21}\n";
  return path;
}

}  // namespace

TEST(InverseModelSigma, AGivenModelSigmaWidensTheRangeBySigmaEffOverSigma) {
  const Study study = read_study(one_observation_study("model_sigma", "0.02").string());
  ASSERT_DOUBLE_EQ(study.observations[0].effective_sigma(), std::sqrt(0.01 * 0.01 + 0.02 * 0.02));
  InversionOptions options;
  options.out_dir = fresh_dir("model_sigma/out").string();
  options.model_version = "test";
  const InversionSummary s = run_inversion(study, options);
  const BoundingFriction& f = s.friction;
  ASSERT_TRUE(f.available && f.with_model_sigma) << f.why_not;
  const double with_model = f.delta1.high - f.delta1.low;
  const double alone = f.delta1_observations.high - f.delta1_observations.low;
  ASSERT_GT(alone, 0.0);
  EXPECT_NEAR(with_model / alone, std::sqrt(5.0), 0.05 * std::sqrt(5.0))
      << "with " << with_model << ", observations only " << alone;
  // The sentence gives both bounds.
  EXPECT_NE(bounding_friction_sentence(study, f).find("observations only"), std::string::npos);
  // Also when the range with the spread reaches the search bound (section VII's coarse-to-fine
  // study at revision 2026-11-27.6 printed only the reading with the spread there).
  BoundingFriction at_bound = f;
  at_bound.delta4.high_at_bound = true;
  at_bound.delta4_observations.high_at_bound = false;
  const std::string sentence = bounding_friction_sentence(study, at_bound);
  EXPECT_NE(sentence.find("no lower bound was found"), std::string::npos) << sentence;
  EXPECT_NE(sentence.find("(observations only: >= "), std::string::npos) << sentence;
}

TEST(InverseModelSigma, AnEnsembleModelSigmaIsMeasuredOnceAtTheStartAndCached) {
  // model_sigma: ensemble runs the study's K realisations at the start point before the
  // fit; a resumed study finds all of them in the cache and runs none again.
  std::string text;
  {
    std::ifstream in(one_observation_study("model_sigma_ensemble", "ensemble"));
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const fs::path path = fs::path(DDAFIT_TEST_TMP) / "model_sigma_ensemble" / "study.yaml";
  std::ofstream(path) << text << "ensemble: 4\n";
  const Study study = read_study(path.string());
  ASSERT_TRUE(study.observations[0].model_sigma_from_ensemble);
  InversionOptions options;
  options.out_dir = fresh_dir("model_sigma_ensemble/out").string();
  options.model_version = "test";
  int forward_runs = 0;
  const ForwardModel counting = [&](const Scene& scene) {
    ++forward_runs;
    return run_forward(scene);
  };
  const InversionSummary first = run_inversion(study, options, counting);
  ASSERT_EQ(first.observations.size(), 1u);
  // Two sliders on planes: nothing amplifies a 1e-6 nudge, so the measured spread is tiny
  // but measured (>= 0), and sigma_eff stays within a hair of sigma.
  EXPECT_GE(first.observations[0].model_sigma, 0.0);
  EXPECT_LT(first.observations[0].model_sigma, 1e-3);
  bool noted = false;
  for (const std::string& n : first.notes) noted = noted || n.find("model_sigma =") != std::string::npos;
  EXPECT_TRUE(noted);
  options.resume = true;
  forward_runs = 0;
  const InversionSummary again = run_inversion(study, options, counting);
  EXPECT_EQ(again.observations[0].model_sigma, first.observations[0].model_sigma);
  EXPECT_EQ(forward_runs, 0) << "every realisation and every fit point came from the cache";
}
