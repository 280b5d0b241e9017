// The stable-state search (forward/analysis/stable_friction.hpp): a trial is stable when
// its motion has died out, judged on the speeds over the trial's last second, not on how
// far a point moved.
#include <gtest/gtest.h>

#include <cmath>

#include "forward/analysis/stable_friction.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

const double kAlpha = std::atan(0.5) * 180.0 / M_PI;  // the 2:1 incline's angle, deg

// The 2:1 incline on one solver, and a search of its interface from `low` to 35 deg with
// 2 s trials.
struct InclineSearch {
  Scene scene;
  StableSearchOptions options;
  InclineSearch(Integrator solver, double low) : scene(verification::incline_scene({})) {
    scene.options.integrator = solver;
    options.interface = 0;
    options.low = low;
    options.high = 35.0;
    options.trial_duration = 2.0;
  }
  StableSearchResult run() const { return find_stable_friction(scene, options); }
};

class StableSearchSolver : public ::testing::TestWithParam<Integrator> {};

TEST_P(StableSearchSolver, BracketsTheInclineAngleOnEachSolver) {
  // A block at rest on a 2:1 slope holds exactly when phi >= alpha = 26.565 deg. Just
  // below, it accelerates at g cos(alpha) (tan alpha - tan phi): 0.1 deg below alpha that
  // is 0.018 m/s^2, 0.04 m/s after 2 s, under rest_speed, but rising; so the bracket must
  // hold alpha to within the search tolerance, plus the 0.08 deg below which a 2 s trial
  // cannot tell the halves' rise of 0.375 a from 10 % + kRiseAllowance x rest_speed.
  InclineSearch search(GetParam(), 20.0);
  search.options.tolerance = 0.25;
  const StableSearchResult r = search.run();
  ASSERT_TRUE(r.bracketed) << r.message;
  EXPECT_LE(r.high - r.low, search.options.tolerance);
  EXPECT_LE(r.low, kAlpha + 0.08);
  EXPECT_GE(r.high, kAlpha - 0.08);
}

TEST_P(StableSearchSolver, SlowAcceleratingCreepBelowRestSpeedIsNotRest) {
  // 0.1 deg below alpha the block is still under rest_speed after 2 s, but speeding up.
  const InclineSearch search(GetParam(), kAlpha - 0.1);
  const StableSearchResult r = search.run();
  ASSERT_FALSE(r.trials.empty());
  const StableTrial& creep = r.trials.front();
  EXPECT_LT(creep.window_speed, search.scene.rest_speed) << "the creep is slower than rest_speed";
  EXPECT_TRUE(creep.rising);
  EXPECT_FALSE(creep.stable);
}

TEST_P(StableSearchSolver, ABlockCreepingAtASteadySpeedAboveRestSpeedIsNotStable) {
  // At phi = alpha a block started at 0.3 m/s down the slope keeps that speed: not rising,
  // not at rest. At 35 deg the same block stops within a tenth of a second: stable.
  InclineSearch search(GetParam(), kAlpha);
  search.scene.blocks[1].velocity = 0.3 * Vec2(2.0, -1.0).normalized();
  search.options.tolerance = 5.0;
  const StableSearchResult r = search.run();
  ASSERT_TRUE(r.bracketed) << r.message;
  const StableTrial& creep = r.trials.front();
  EXPECT_NEAR(creep.end_speed, 0.3, 0.01) << "Coulomb friction at phi = alpha exactly balances gravity";
  EXPECT_FALSE(creep.rising);
  EXPECT_FALSE(creep.stable);
  EXPECT_TRUE(r.trials[1].stable);
}

TEST_P(StableSearchSolver, AnElasticColumnThatSettlesButDoesNotSlideIsStable) {
  // A 20 m elastic column (E = 3.5e8 Pa, the substep solver's blocks elastic too) on a
  // level base settles under its own weight and rings down: it moves, but nothing slides.
  // On a level base friction plays no part, so it is stable at the low bound already. A
  // displacement rule tighter than the settling calls the same run moving.
  verification::InclineSetup setup;
  Scene scene = verification::incline_scene(setup);
  scene.blocks.clear();
  scene.materials[0].young_modulus = 3.5e8;
  scene.blocks.push_back(verification::block("base", {{-5, -2}, {6, -2}, {6, 0}, {-5, 0}}, true));
  scene.blocks.push_back(verification::block("column", {{0, 0}, {1, 0}, {1, 20}, {0, 20}}, false));
  scene.measure = {{"top", {0.5, 19.5}}};
  scene.options.integrator = GetParam();
  scene.options.rigid_blocks = false;
  StableSearchOptions o;
  o.interface = 0;
  o.low = 20.0;
  o.high = 35.0;
  o.trial_duration = 3.0;
  const StableSearchResult r = find_stable_friction(scene, o);
  ASSERT_FALSE(r.trials.empty());
  const StableTrial& t = r.trials.front();
  EXPECT_TRUE(t.failure.empty()) << t.failure;
  EXPECT_GT(t.movement, 1e-4) << "the column settles";
  EXPECT_TRUE(t.stable) << "window speed " << t.window_speed << " m/s, rising " << t.rising;
  EXPECT_FALSE(r.bracketed) << "stable at the low bound: the search says so";
  o.max_movement = 0.5 * t.movement;
  EXPECT_FALSE(find_stable_friction(scene, o).trials.front().stable) << "the optional displacement rule still applies";
}

INSTANTIATE_TEST_SUITE_P(Solvers, StableSearchSolver, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace ddafit
