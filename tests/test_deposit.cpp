// The deposit observation: the ground surface a run leaves (forward/top_surface)
// against a surveyed one, as an RMS elevation misfit (issue "Which weakening explains
// Vajont?"). Geometry checked against hand values; the observation checked by a twin whose
// surveyed surface is the truth run's own.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "forward/top_surface.hpp"
#include "forward/simulation.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/inversion.hpp"
#include "verify/cases.hpp"

namespace {

namespace fs = std::filesystem;
using namespace ddafit;
using namespace ddafit::inverse;

TEST(TopSurface, IsTheHighestEdgeOfAnyBlockInEachColumn) {
  // A 10 m base whose top rises from y 1 to 3 over x 0..2 and falls to 1 at x 10, and a 2 m
  // block above it on x 4..6 with its top at 5: every column's top is known by hand.
  Scene s = verification::stack_scene();
  s.blocks.clear();
  s.blocks.push_back(verification::block("base", {{0, 0}, {10, 0}, {10, 1}, {2, 3}, {0, 1}}, true));
  s.blocks.push_back(verification::block("block", {{4, 3}, {6, 3}, {6, 5}, {4, 5}}, false));
  const BlockSystem system = build_block_system(s);
  const std::vector<Vec2> top = top_surface(system, 20);  // 0.5 m columns
  ASSERT_EQ(top.size(), 20u);
  for (const Vec2& p : top) {
    const double base = p.x() <= 2.0 ? 1.0 + p.x() : 3.0 - 2.0 * (p.x() - 2.0) / 8.0;
    const double expected = p.x() >= 4.0 && p.x() <= 6.0 ? 5.0 : base;
    EXPECT_NEAR(p.y(), expected, 1e-12) << "x " << p.x();
  }
  // RMS against a flat 1 m surface over x in [4, 6]: the block's top 4 m above it.
  EXPECT_NEAR(surface_misfit_rms(top, {{0, 1}, {10, 1}}, 4.0, 6.0), 4.0, 1e-12);
  EXPECT_TRUE(std::isnan(surface_misfit_rms(top, {{0, 1}, {10, 1}}, 20.0, 30.0)));
}

// The twin: the two sliders' final surface at the truth (30 % degradation) is the survey;
// a study that fits the degradation to that deposit alone finds the truth, where the
// deposit misfit is zero.
TEST(DepositObservation, ATwinRecoversTheDegradationFromTheDepositAlone) {
  const std::string scene = std::string(DDAFIT_CASES_DIR) + "/inverse/two_sliders.yaml";
  const SimulationResult truth = run_forward(io::read_scene(scene, {{"interfaces.clay.degradation_percent", "30"}}));
  ASSERT_EQ(truth.summary.status, RunStatus::Completed) << truth.summary.message;
  ASSERT_GT(truth.summary.final_surface.size(), 100u);
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / "deposit_twin";
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    std::ofstream csv(dir / "after.csv");
    csv << "x_m,z_m\n";
    for (const Vec2& p : truth.summary.final_surface) csv << exact_text(p.x()) << "," << exact_text(p.y()) << "\n";
  }
  const double x0 = truth.summary.final_surface.front().x(), x1 = truth.summary.final_surface.back().x();
  std::ofstream(dir / "study.yaml")
      << "scene: " << scene << "\nparameters:\n"
      << "  - {name: basal_degradation, key: interfaces.clay.degradation_percent, lower: 0, upper: 60, start: 10,"
      << " resolution: 0.5}\nobservations:\n"
      << "  - {quantity: deposit_rms, surface: after.csv, from: " << x0 << ", to: " << x1 << ", value: 0, sigma: 0.01}\n"
      << "method: {optimizer: nlopt, algorithm: LN_BOBYQA, budget: 30}\nprofile: {points: 5}\n";
  const Study study = read_study((dir / "study.yaml").string());
  check_study_against_scene(study);
  ASSERT_TRUE(study.observations[0].is_deposit());
  InversionOptions options;
  options.out_dir = (dir / "out").string();
  options.model_version = "test";
  const InversionSummary s = run_inversion(study, options);
  const LevelFit& best = s.levels[s.best_level];
  ASSERT_FALSE(best.best.failed) << best.best.message;
  // Within two resolutions (the twin tests' rule, tests/test_inverse.cpp); the surface is
  // the truth's own, so its misfit there is zero.
  EXPECT_NEAR(best.best.values[0], 30.0, 1.0);
  std::printf("[deposit twin] degradation %.3f (true 30), deposit RMS %.4g m, %ld runs\n", best.best.values[0],
              best.best.simulated[0], s.run);
}

TEST(DepositObservation, TheStudyFileSaysWhatADepositNeeds) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / "deposit_bad";
  fs::create_directories(dir);
  const std::string head = "scene: " + std::string(DDAFIT_CASES_DIR) +
                           "/inverse/two_sliders.yaml\nparameters:\n  - {name: d, key: interfaces.clay.degradation_percent,"
                           " lower: 0, upper: 60, start: 10, resolution: 0.5}\nobservations:\n";
  const auto fails_with = [&](const std::string& obs, const std::string& key, const std::string& words) {
    std::ofstream(dir / "study.yaml") << head << obs;
    try {
      read_study((dir / "study.yaml").string());
    } catch (const StudyError& e) {
      const std::string m = e.what();
      return m.find(key) != std::string::npos && m.find(words) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(fails_with("  - {quantity: deposit_rms, from: 0, to: 5, value: 0, sigma: 1}\n", "observations[0].surface",
                         "CSV"));
  EXPECT_TRUE(fails_with("  - {quantity: deposit_rms, surface: none.csv, from: 0, to: 5, value: 0, sigma: 1}\n",
                         "observations[0].surface", "none.csv"));
  EXPECT_TRUE(fails_with("  - {point: A, quantity: deposit_rms, surface: x.csv, from: 0, to: 5, value: 0, sigma: 1}\n",
                         "observations[0].point", "no point"));
  EXPECT_TRUE(fails_with("  - {point: A, quantity: peak_total_velocity, value: 1, sigma: 1, from: 2}\n",
                         "observations[0].from", "only for quantity: deposit_rms"));
}

}  // namespace
