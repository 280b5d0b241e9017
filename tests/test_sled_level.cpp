// A study's block-size levels may start with the sled (`levels: [sled, 20, 10]`): the first
// level runs at fidelity 0 on a cut at the next level's block size, the later ones the DDA
// solvers; `sled` anywhere else is refused naming the entry.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "inverse/forward_call.hpp"
#include "inverse/study.hpp"
#include "tests/cli_run.hpp"

namespace ddafit::inverse {
namespace {

std::string study_text(const std::string& levels) {
  return "scene: " + std::string(DDAFIT_CASES_DIR) + "/slab/slab.yaml\n"
         "settings: {time.duration: 6, time.integrator: substep}\n"
         "parameters:\n"
         "  - {name: base_loss, key: interfaces.base.degradation_percent, lower: 0, upper: 60, start: 20, resolution: 1}\n"
         "  - {name: block_size, key: mesh.block_size, levels: " + levels + "}\n"
         "observations:\n"
         "  - {point: top, quantity: max_lateral_displacement, value: 30, sigma: 5}\n"
         "method: {optimizer: nlopt, algorithm: LN_BOBYQA, budget: 4, levels: coarse_to_fine, fine_budget: 3}\n";
}

std::string write_study(const std::string& tag, const std::string& levels) {
  return ddafit_test::write_file(tag, "study.yaml", study_text(levels)).string();
}

TEST(SledLevel, TheFirstLevelRunsTheSledOnTheNextLevelsCut) {
  const Study study = read_study(write_study("sled_level", "[sled, 20, 10]"));
  ASSERT_EQ(study.parameters[1].levels.size(), 3u);
  EXPECT_EQ(study.parameters[1].levels[0], kSledLevel);
  const StudyScene scene(study);
  ASSERT_TRUE(scene.problem().empty()) << scene.problem();
  const Scene sled = scene.at({20.0, kSledLevel});
  EXPECT_EQ(sled.options.integrator, Integrator::Sled);
  EXPECT_EQ(sled.mesh.block_size, 20.0);
  const Scene coarse = scene.at({20.0, 20.0});
  EXPECT_EQ(coarse.options.integrator, Integrator::Substep);
  EXPECT_EQ(coarse.blocks.size(), sled.blocks.size()) << "the sled is cut as the next level is";
  const SimulationResult run = simulate(sled);
  ASSERT_EQ(run.summary.status, RunStatus::Completed) << run.summary.message;
  EXPECT_FALSE(run.sled.series.empty());
}

TEST(SledLevel, SledAnywhereButFirstOrOnAnotherKeyIsRefused) {
  for (const std::string& levels : {std::string("[20, sled]"), std::string("[sled]")}) {
    try {
      read_study(write_study("sled_level_bad", levels));
      ADD_FAILURE() << "accepted levels " << levels;
    } catch (const StudyError& e) {
      EXPECT_NE(std::string(e.what()).find("sled is the first level"), std::string::npos) << e.what();
    }
  }
}

TEST(SledLevel, OnlyTheWordSledMakesASledLevel) {
  // A numeric level 0 of another key is a value, not the sled.
  const std::string text = study_text("[20, 10]");
  const std::string zero = text.substr(0, text.find("  - {name: base_loss")) +
                           "  - {name: base_loss, key: interfaces.base.degradation_percent, levels: [0, 25]}\n"
                           "  - {name: joint, key: interfaces.joint.roughness_angle, lower: 0, upper: 10, start: 5, resolution: 1}\n" +
                           text.substr(text.find("observations:"));
  const Study study = read_study(ddafit_test::write_file("sled_level_zero", "study.yaml", zero).string());
  EXPECT_FALSE(study.parameters[0].sled_first);
  const StudyScene scene(study);
  ASSERT_TRUE(scene.problem().empty()) << scene.problem();
  EXPECT_EQ(scene.at({0.0, 5.0}).options.integrator, Integrator::Substep);
}

TEST(SledLevel, AThermalPressurizationInterfaceCannotStartOnTheSled) {
  std::string text = study_text("[sled, 20]");
  text.replace(text.find("settings: {"), 11,
               "settings: {interfaces.base.law: thermal_pressurization, ");
  text.replace(text.find("  - {name: base_loss"), text.find("  - {name: block_size") - text.find("  - {name: base_loss"),
               "  - {name: band, key: interfaces.base.band_thickness, lower: 0.001, upper: 0.1, start: 0.01, resolution: 0.001}\n");
  const Study study = read_study(ddafit_test::write_file("sled_level_tp", "study.yaml", text).string());
  try {
    check_study_against_scene(study);
    ADD_FAILURE() << "a thermal-pressurization study was allowed to start on the sled";
  } catch (const StudyError& e) {
    EXPECT_NE(std::string(e.what()).find("sled cannot run interface 'base'"), std::string::npos) << e.what();
  }
}

TEST(SledLevel, InvertExploresOnTheSledAndReportsTheFinestLevel) {
  const std::string path = write_study("sled_level_invert", "[sled, 20]");
  const std::string out = std::string(DDAFIT_TEST_TMP) + "/sled_level_invert/out";
  std::filesystem::remove_all(out);
  const ddafit_test::CommandResult r = ddafit_test::ddafit("invert " + path + " --threads 1 --quiet --out " + out, "sled_level_invert");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ddafit_test::slurp(out + "/report.json"));
  ASSERT_EQ(j.at("levels").size(), 2u);
  std::cout << "[measured] slab, levels [sled, 20]: " << j.at("levels").dump().substr(0, 400) << "\n";
}

TEST(SledLevel, MultiFidelityCorrectsTheSledWithRunsOfTheFinerLevel) {
  // levels: multi_fidelity with [sled, 20]: the sled is fitted and profiled, three runs of
  // the DDA slab (20 m blocks) correct it, and the report's level 2 is the best of them.
  std::string text = study_text("[sled, 20]");
  text.replace(text.find("levels: coarse_to_fine, fine_budget: 3"), 38, "levels: multi_fidelity");
  text += "profile: {points: 5}\n";
  const std::string path = ddafit_test::write_file("sled_level_multi_fidelity", "study.yaml", text).string();
  const std::string out = std::string(DDAFIT_TEST_TMP) + "/sled_level_multi_fidelity/out";
  std::filesystem::remove_all(out);
  const ddafit_test::CommandResult r =
      ddafit_test::ddafit("invert " + path + " --threads 1 --jobs 2 --quiet --out " + out, "sled_level_multi_fidelity");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ddafit_test::slurp(out + "/report.json"));
  EXPECT_EQ(j.at("level_strategy"), "multi_fidelity");
  ASSERT_EQ(j.at("levels").size(), 2u);
  EXPECT_EQ(j.at("levels")[1].at("level").at("block_size"), 20.0);
  const nlohmann::json& mf = j.at("multi_fidelity");
  EXPECT_EQ(mf.at("coarse_level"), kSledLevel);
  ASSERT_GE(mf.at("runs").size(), 2u);
  ASSERT_LE(mf.at("runs").size(), 3u);
  for (const nlohmann::json& run : mf.at("runs")) EXPECT_FALSE(run.at("fine_failed").get<bool>());
  EXPECT_TRUE(j.at("bounding_friction").at("available").get<bool>());
  std::cout << "[measured] slab, multi_fidelity [sled, 20]: " << mf.at("correction").dump() << ", RMS "
            << mf.at("rms_sigma") << " sigma\n";
}

}  // namespace
}  // namespace ddafit::inverse
