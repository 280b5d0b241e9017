// Block-size advice (forward/analysis/block_size_advice.hpp, `ddafit advise`): the coarsest
// size within the tolerance of the next finer, the tolerance widened by the runs' own spread,
// and a plain "keeps moving" when no size converges.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "forward/analysis/block_size_advice.hpp"
#include "tests/cli_run.hpp"

namespace ddafit {
namespace {

LadderRung rung(double size, double mean, double sd, int completed = 3) {
  LadderRung r;
  r.block_size = size;
  r.value.mean = mean;
  r.value.standard_deviation = sd;
  r.completed = completed;
  return r;
}

TEST(BlockSizeAdvice, TheCoarsestSizeWithinTheToleranceOfTheNextFinerIsRecommended) {
  // 100 -> 96: 4.2 % (inside 5 %); the coarsest converged pair wins.
  const BlockSizeAdvice a = advise_block_size({rung(40, 100, 0), rung(20, 96, 0), rung(10, 95, 0)}, 0.05);
  ASSERT_EQ(a.recommended, 0);
  EXPECT_NEAR(a.change[0], 4.0 / 96.0, 1e-12);
  EXPECT_NE(a.verdict.find("use block_size 40 m"), std::string::npos) << a.verdict;
  // 100 -> 90 (11 %) does not; 90 -> 88 (2.3 %) does: the middle size.
  const BlockSizeAdvice b = advise_block_size({rung(40, 100, 0), rung(20, 90, 0), rung(10, 88, 0)}, 0.05);
  EXPECT_EQ(b.recommended, 1) << b.verdict;
}

TEST(BlockSizeAdvice, AnAnswerThatKeepsMovingIsSaidPlainly) {
  const BlockSizeAdvice a = advise_block_size({rung(40, 100, 0), rung(20, 80, 0), rung(10, 64, 0)}, 0.05);
  EXPECT_EQ(a.recommended, -1);
  EXPECT_NE(a.verdict.find("keeps moving with block size"), std::string::npos) << a.verdict;
}

TEST(BlockSizeAdvice, TheToleranceIsNeverTighterThanTheRunsOwnSpread) {
  // 100 -> 90 is 11 %, but each mean scatters by 4: 2 sqrt(4^2 + 4^2) / 90 = 12.6 % allowed.
  const BlockSizeAdvice a = advise_block_size({rung(40, 100, 4), rung(20, 90, 4)}, 0.05);
  ASSERT_EQ(a.recommended, 0) << a.verdict;
  EXPECT_NEAR(a.allowed[0], 2.0 * std::hypot(4.0, 4.0) / 90.0, 1e-12);
  EXPECT_NE(a.verdict.find("own spread"), std::string::npos) << a.verdict;
  // A rung whose runs all failed gives no answer: it converges with nothing.
  const BlockSizeAdvice b = advise_block_size({rung(40, 100, 0), rung(20, 0, 0, 0), rung(10, 100, 0)}, 0.05);
  EXPECT_EQ(b.recommended, -1);
}

TEST(BlockSizeAdvice, TheCommandCutsTheSlabAtEachSizeAndWritesItsAdvice) {
  const std::string scene = std::string(DDAFIT_CASES_DIR) + "/slab/slab.yaml";
  const std::string out = std::string(DDAFIT_TEST_TMP) + "/advise_slab";
  const ddafit_test::CommandResult r = ddafit_test::ddafit(
      "advise " + scene + " --point top --sizes 10,20,15 --ensemble 2 --set time.duration=5 --threads 1 --out " + out,
      "advise_slab_run");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ddafit_test::slurp(out + "/advise.json"));
  const auto& rungs = j.at("rungs");
  ASSERT_EQ(rungs.size(), 3u);
  // Coarse to fine, each cut by the mesher to more blocks.
  EXPECT_EQ(rungs[0].at("block_size").get<double>(), 20.0);
  EXPECT_LT(rungs[0].at("free_blocks").get<int>(), rungs[2].at("free_blocks").get<int>());
  // The recommendation is the first rung whose change is inside what it is allowed.
  int first = -1;
  for (size_t k = 0; k + 1 < rungs.size() && first < 0; ++k)
    if (!rungs[k].at("change_to_next_finer").is_null() &&
        rungs[k].at("change_to_next_finer").get<double>() <= rungs[k].at("allowed").get<double>())
      first = static_cast<int>(k);
  if (first < 0) {
    EXPECT_TRUE(j.at("recommended_block_size").is_null());
  } else {
    EXPECT_EQ(j.at("recommended_block_size").get<double>(), rungs[first].at("block_size").get<double>());
  }
  // Refused in one line: an unknown quantity; a scene of explicit blocks (nothing to re-cut).
  EXPECT_EQ(ddafit_test::ddafit("advise " + scene + " --point top --quantity speed --out " + out, "advise_bad_q").code, 2);
  const ddafit_test::CommandResult explicit_blocks = ddafit_test::ddafit(
      "advise " + std::string(DDAFIT_CASES_DIR) + "/verification/incline_i5.yaml --point P1 --out " + out, "advise_bad_scene");
  EXPECT_EQ(explicit_blocks.code, 2);
  EXPECT_NE(explicit_blocks.err.find("regions"), std::string::npos) << explicit_blocks.err;
}

}  // namespace
}  // namespace ddafit
