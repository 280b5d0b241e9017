// The back-analysis library: twin experiments (observations made by a forward run at
// known parameters must be recovered by NLopt and by Ceres), the evaluation cache, and
// the bounding friction of the profile.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "inverse/evaluation_cache.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/inversion.hpp"
#include "inverse/objective.hpp"
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

// A study over the two sliders whose observations are a forward run at the truth.
fs::path twin_study(const std::string& tag, const std::string& method, int profile_points) {
  const SimulationResult truth =
      run_forward(kScene, {{"interfaces.clay.degradation_percent", exact_text(kTrueDegradation)},
                           {"interfaces.joint.roughness_angle", exact_text(kTrueRoughness)}});
  EXPECT_EQ(truth.summary.status, RunStatus::Completed) << truth.summary.message;
  std::string obs;
  for (const PointSummary& p : truth.summary.points)
    obs += "  - {point: " + p.name + ", quantity: max_total_displacement, value: " +
           exact_text(p.max_total_displacement) + ", sigma: 0.01}\n" + "  - {point: " + p.name +
           ", quantity: peak_total_velocity, value: " + exact_text(p.peak_total_velocity) + ", sigma: 0.01}\n";
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

}  // namespace
