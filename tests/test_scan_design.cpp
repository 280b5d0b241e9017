// Scans over a design (inverse/scan_design.hpp) on the twin study: the cache makes a killed
// scan resume without repeating a run, and running several at a time changes nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>

#include "inverse/evaluation_cache.hpp"
#include "inverse/inversion.hpp"
#include "inverse/objective.hpp"
#include "inverse/scan_design.hpp"
#include "inverse/study.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ddafit;
using namespace ddafit::inverse;

const std::string kStudy = std::string(DDAFIT_CASES_DIR) + "/inverse/twin_study.yaml";

fs::path fresh_dir(const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

InversionOptions options_in(const fs::path& dir, bool resume, int jobs) {
  InversionOptions o;
  o.out_dir = dir.string();
  o.resume = resume;
  o.model_version = "test";
  o.jobs = jobs;
  return o;
}

// The real twin forward model, counting its calls (from any thread).
ForwardModel counting(std::atomic<int>* calls) {
  return [calls](const Scene& scene) {
    ++*calls;
    return run_forward(scene);
  };
}

TEST(ScanDesign, AKilledScanResumesWithNoRunRepeated) {
  // A scan killed after 5 of its runs left those 5 in the cache (each run is committed as it
  // ends, as after kill -9 of `invert`). The resumed scan must run exactly the others.
  const Study study = read_study(kStudy);
  DesignOptions design;
  design.kind = DesignKind::LatinHypercube;
  design.samples = 6;
  const std::vector<std::vector<double>> points = design_values(study, design);  // 6 x 2 block-size levels
  ASSERT_EQ(points.size(), 12u);
  const fs::path dir = fresh_dir("scan_resume");
  {
    EvaluationCache cache((dir / "evaluations.sqlite").string(), "test", scene_input_hash(study));
    Objective killed(study, cache, run_forward);
    for (size_t k = 0; k < 5; ++k) killed.evaluate(points[k]);
  }
  std::atomic<int> calls{0};
  const DesignResult r = run_design(study, options_in(dir, true, 1), design, counting(&calls));
  EXPECT_EQ(calls.load(), 7);
  EXPECT_EQ(r.cached, 5);
  EXPECT_EQ(r.run, 7);
  ASSERT_EQ(r.runs.size(), 12u);
}

TEST(ScanDesign, TwoJobsGiveTheSameChi2PerPointAsOne) {
  // The forward model is deterministic and shares nothing between runs: running two at a
  // time must give bit-identical chi2 at every point, in the same order.
  const Study study = read_study(kStudy);
  DesignOptions design;
  design.kind = DesignKind::Morris;
  design.trajectories = 3;
  std::atomic<int> calls_one{0}, calls_two{0};
  const DesignResult one = run_design(study, options_in(fresh_dir("scan_jobs_1"), false, 1), design, counting(&calls_one));
  const DesignResult two = run_design(study, options_in(fresh_dir("scan_jobs_2"), false, 2), design, counting(&calls_two));
  ASSERT_EQ(one.runs.size(), two.runs.size());
  for (size_t k = 0; k < one.runs.size(); ++k) {
    EXPECT_EQ(one.runs[k].values, two.runs[k].values) << k;
    EXPECT_EQ(one.runs[k].chi2, two.runs[k].chi2) << k;
  }
  EXPECT_EQ(calls_one.load(), calls_two.load());  // no point run twice in either
  EXPECT_EQ(one.best, two.best);
}

TEST(ScanDesign, InvertWithTwoJobsReportsTheSameBoundingFriction) {
  // The profile's grid runs as one batch; with two jobs the fit, the grid and the
  // bisection must see the same chi2 values and end on the same bound.
  const Study study = read_study(kStudy);
  const InversionSummary one = run_inversion(study, options_in(fresh_dir("invert_jobs_1"), false, 1));
  const InversionSummary two = run_inversion(study, options_in(fresh_dir("invert_jobs_2"), false, 2));
  ASSERT_TRUE(one.friction.available && two.friction.available);
  EXPECT_EQ(one.friction.delta4.mu_low, two.friction.delta4.mu_low);
  EXPECT_EQ(one.friction.delta1.mu_low, two.friction.delta1.mu_low);
  EXPECT_EQ(one.evaluations, two.evaluations);
}

}  // namespace
