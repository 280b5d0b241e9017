// method.levels: multi_fidelity (inverse/multi_fidelity.hpp). A stand-in forward model whose
// answers are known functions of the basal degradation d at two levels (the time step plays
// the block size): the fine level is the coarse one plus a bias. Where the bias is linear in
// d, the corrected coarse profile must be the fine profile, found with the planned number of
// fine runs; where it is curved, the report must say how far the fine runs sit off it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "forward/io/scene_reader.hpp"
#include "inverse/inversion.hpp"
#include "inverse/report.hpp"
#include "inverse/study.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ddafit;
using namespace ddafit::inverse;

const std::string kScene = std::string(DDAFIT_CASES_DIR) + "/inverse/two_sliders.yaml";
constexpr double kCoarseStep = 0.002, kFineStep = 0.001;
constexpr double kTruth = 30.0;       // % degradation of the fine level's observations
constexpr double kResolution = 0.5;   // of the study's degradation

// The stand-in's runout and speed at the coarse level, and a bias for the fine one.
double coarse_runout(double d) { return 50.0 + 2.0 * d + 0.01 * d * d; }
double coarse_speed(double d) { return 5.0 + 0.1 * d; }
struct Bias {
  double runout_a = 15.0, runout_b = -0.3, runout_curve = 0.0;  // a + b d + curve (d - 30)^2
  double speed_a = 1.0, speed_b = 0.02;
  double runout(double d) const { return runout_a + runout_b * d + runout_curve * (d - kTruth) * (d - kTruth); }
  double speed(double d) const { return speed_a + speed_b * d; }
};
double fine_runout(double d, const Bias& b) { return coarse_runout(d) + b.runout(d); }
double fine_speed(double d, const Bias& b) { return coarse_speed(d) + b.speed(d); }

double degradation_of(const Scene& scene) {
  for (const Interface& f : scene.interfaces)
    if (f.name == "clay" && f.degradation_percent) return *f.degradation_percent;
  return NAN;
}

struct StandIn {
  Bias bias;
  int* fine_runs;
  SimulationResult operator()(const Scene& scene) const {
    const double d = degradation_of(scene);
    const bool fine = scene.max_step == kFineStep;
    if (fine) ++*fine_runs;
    SimulationResult r;
    r.summary.status = RunStatus::Completed;
    PointSummary a;
    a.name = "A";
    a.max_total_displacement = fine ? fine_runout(d, bias) : coarse_runout(d);
    a.peak_total_velocity = fine ? fine_speed(d, bias) : coarse_speed(d);
    r.summary.points = {a};
    r.history.push_back(HistoryRow{});  // a run has a history; the report keeps the best one's
    return r;
  }
};

constexpr double kRunoutSigma = 2.0, kSpeedSigma = 0.2;

fs::path study_file(const std::string& tag, const std::string& method, const Bias& bias) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "study.yaml";
  std::ofstream(path) << "scene: " << kScene << "\n"
                      << "parameters:\n"
                      << "  - {name: step, key: time.step, levels: [" << kCoarseStep << ", " << kFineStep << "]}\n"
                      << "  - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 0, upper: 60,"
                      << " start: 10, resolution: " << kResolution << "}\n"
                      << "observations:\n"
                      << "  - {point: A, quantity: max_total_displacement, value: " << exact_text(fine_runout(kTruth, bias))
                      << ", sigma: " << kRunoutSigma << "}\n"
                      << "  - {point: A, quantity: peak_total_velocity, value: " << exact_text(fine_speed(kTruth, bias))
                      << ", sigma: " << kSpeedSigma << "}\n"
                      << "method: " << method << "\n"
                      << "profile: {points: 7}\n";
  return path;
}

// Where the fine level's own chi^2 (the truth at kTruth, chi^2 = 0 there) crosses `level`,
// below and above the truth: bisection to 1e-9 on the known functions.
std::pair<double, double> fine_crossings(const Bias& b, double level) {
  const auto chi2 = [&](double d) {
    const double r = (fine_runout(d, b) - fine_runout(kTruth, b)) / kRunoutSigma;
    const double v = (fine_speed(d, b) - fine_speed(kTruth, b)) / kSpeedSigma;
    return r * r + v * v;
  };
  const auto cross = [&](double inside, double outside) {
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (inside + outside);
      (chi2(mid) <= level ? inside : outside) = mid;
    }
    return inside;
  };
  return {cross(kTruth, 0.0), cross(kTruth, 60.0)};
}

InversionSummary invert(const fs::path& path, const Bias& bias, int* fine_runs) {
  const Study study = read_study(path.string());
  InversionOptions options;
  options.out_dir = (path.parent_path() / "out").string();
  options.model_version = "test";
  return run_inversion(study, options, StandIn{bias, fine_runs});
}

TEST(MultiFidelity, ALinearBiasGivesTheFineProfileFromThreeFineRuns) {
  const Bias bias;  // linear in d
  int fine_runs = 0;
  const fs::path path = study_file("multi_fidelity_linear", "{budget: 40, levels: multi_fidelity}", bias);
  const InversionSummary s = invert(path, bias, &fine_runs);
  // Three fine runs (the default): two across the coarse range, one at the corrected optimum.
  EXPECT_EQ(fine_runs, 3);
  EXPECT_EQ(s.history_reruns, 0) << "the best fine run's history came from the cache";
  ASSERT_EQ(s.levels.size(), 2u);
  EXPECT_EQ(s.best_level, 1);
  ASSERT_TRUE(s.fidelity.used);
  // A line through fine - coarse recovers a linear bias to round-off.
  EXPECT_NEAR(s.fidelity.offset[0], bias.runout_a, 1e-9);
  EXPECT_NEAR(s.fidelity.slope[0], bias.runout_b, 1e-11);
  EXPECT_NEAR(s.fidelity.slope[1], bias.speed_b, 1e-11);
  EXPECT_LT(s.fidelity.rms_sigma, 1e-9);
  const BoundingFriction& f = s.friction;
  ASSERT_TRUE(f.available) << f.why_not;
  EXPECT_TRUE(f.corrected);
  // The corrected profile's ranges are the fine level's: the bisection stops at 1.5
  // resolutions and interpolates in sqrt(Delta chi^2), exact for a quadratic chi^2 and
  // within a resolution for this one (the runout's d^2 term).
  for (const auto& [range, level] : {std::pair{f.delta1, 1.0}, std::pair{f.delta4, 4.0}}) {
    const auto [low, high] = fine_crossings(bias, level);
    std::printf("[multi_fidelity] Delta chi2 <= %g: corrected [%.3f, %.3f], fine [%.3f, %.3f]\n", level, range.low,
                range.high, low, high);
    EXPECT_NEAR(range.low, low, kResolution) << "Delta chi2 " << level;
    EXPECT_NEAR(range.high, high, kResolution) << "Delta chi2 " << level;
  }
  EXPECT_NEAR(f.best_value, kTruth, kResolution);
  // The reported best is a fine run, at the truth (the check run lands on it).
  EXPECT_EQ(s.levels[1].best.values[0], kFineStep);
  EXPECT_NEAR(s.levels[1].best.values[1], kTruth, kResolution);
  EXPECT_TRUE(s.fidelity.checked);
  EXPECT_NEAR(s.fidelity.check_chi2, s.fidelity.check_predicted_chi2, 1e-9);
  // The report names the strategy and carries the runs.
  write_report((path.parent_path() / "report").string(), read_study(path.string()), s);
  std::ifstream in(path.parent_path() / "report" / "report.json");
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  EXPECT_NE(text.find("\"level_strategy\": \"multi_fidelity\""), std::string::npos);
  EXPECT_NE(text.find("\"rms_sigma\""), std::string::npos);
}

TEST(MultiFidelity, ACurvedBiasShowsInTheFineRunsMisfitAndTheCheck) {
  // A bias with curvature: a line through three fine runs cannot hold it, and the report
  // must say so rather than pass the coarse shape off as the fine one. The fine runs lie a
  // few % apart (across the coarse Delta chi^2 <= 4 range), so the curvature is strong: 1 m
  // per %^2, 9 m (4.5 sigma) of bend 3 % from the truth.
  Bias bias;
  bias.runout_curve = 1.0;
  int fine_runs = 0;
  const fs::path path = study_file("multi_fidelity_curved", "{budget: 40, levels: multi_fidelity}", bias);
  const InversionSummary s = invert(path, bias, &fine_runs);
  EXPECT_EQ(fine_runs, 3);
  EXPECT_EQ(s.history_reruns, 0);
  // A line through three points of a parabola misses each by a third of its sagitta or
  // more; with 4.5 sigma of bend that is well above 0.1 sigma.
  EXPECT_GT(s.fidelity.rms_sigma, 0.1);
}

TEST(MultiFidelity, StudiesThatCannotBeCorrectedAreRefusedNamingTheKey) {
  const Bias bias;
  const auto refused = [&](const std::string& method, const std::string& key) {
    const fs::path path = study_file("multi_fidelity_bad", method, bias);
    try {
      read_study(path.string());
      ADD_FAILURE() << method << " was accepted";
    } catch (const StudyError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refused("{levels: multi_fidelity, fine_runs: 1}", "method.fine_runs");
  refused("{levels: coarse_to_fine, fine_runs: 3}", "method.fine_runs");
  refused("{levels: mixed}", "method.levels");
}

}  // namespace
