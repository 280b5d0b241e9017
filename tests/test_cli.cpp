// The command-line contract: output files, exit codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/cli_run.hpp"

namespace {

namespace fs = std::filesystem;

using namespace ddafit_test;

const std::string kIncline = std::string(DDAFIT_CASES_DIR) + "/verification/incline_i5.yaml";

TEST(Cli, SimulateWritesHistoryAndSummary) {
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "simulate_ok" / "out";
  const CommandResult r = ddafit("simulate " + kIncline + " --out " + out.string() + " --quiet", "simulate_ok");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream csv(out / "history.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "time,point,x,y,ux,uy,vx,vy");  // exact header is part of the contract
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 201);  // t = 0, 0.01, ..., 2.00 s for the one point P1
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  for (const char* key : {"max_lateral_displacement", "max_total_displacement", "peak_lateral_velocity",
                          "peak_total_velocity", "duration", "stopped"})
    EXPECT_TRUE(j["points"]["P1"].contains(key)) << key;
  for (const char* key : {"steps", "open_close_iterations", "step_cuts", "penalty_raises", "wall_seconds"})
    EXPECT_TRUE(j["run"].contains(key)) << key;
  EXPECT_EQ(j["run"]["steps"].get<int>(), 2000);  // 2 s at the largest step, no cuts needed
  // Without control.reuse_factorization every open-close pass factorises once or updates the
  // last factor (settling adds its own passes), and the one contact's pair never changes the
  // sparsity pattern after t = 0 (one block: its pair with the fixed plane adds no
  // off-diagonal block).
  EXPECT_GE(j["run"]["factorizations"].get<long>() + j["run"]["factor_updates"].get<long>(),
            j["run"]["open_close_iterations"].get<long>());
  EXPECT_EQ(j["run"]["cg_solves"].get<long>(), 0);
  EXPECT_EQ(j["run"]["symbolic_analyses"].get<long>(), 1);
  // The block accelerates to 1.194 m/s^2 after 2.2 cm: it never reaches rest in 2 s.
  EXPECT_FALSE(j["points"]["P1"]["stopped"].get<bool>());
  EXPECT_DOUBLE_EQ(j["points"]["P1"]["duration"].get<double>(), 2.0);
  EXPECT_TRUE(j["warnings"].empty());  // 1 ms is in the tested range
}

TEST(Cli, SimulateWithoutSceneRunsBuiltInCase) {
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "simulate_default" / "out";
  const CommandResult r = ddafit("simulate --out " + out.string() + " --quiet", "simulate_default");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "history.csv"));
}

// --mirror runs the scene's mirror image and writes its results read back unmirrored
// (forward/mirror.hpp): on the incline, one block on a plane (implicit solver), the same
// history to rounding (1e-8 m; measured 2e-10 m, test_mirror.cpp) and the same header; with --vtk-interval, whose snapshots would be
// the mirror's, it is refused with one line and exit 2.
TEST(Cli, SimulateMirrorWritesTheHistoryReadBack) {
  const fs::path plain = fs::path(DDAFIT_TEST_TMP) / "simulate_mirror" / "plain";
  const fs::path mirror = fs::path(DDAFIT_TEST_TMP) / "simulate_mirror" / "mirror";
  ASSERT_EQ(ddafit("simulate " + kIncline + " --out " + plain.string() + " --quiet", "simulate_mirror").code, 0);
  const CommandResult r = ddafit("simulate " + kIncline + " --mirror --out " + mirror.string() + " --quiet",
                                 "simulate_mirror");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto a = nlohmann::json::parse(slurp(plain / "summary.json"));
  const auto b = nlohmann::json::parse(slurp(mirror / "summary.json"));
  EXPECT_NEAR(a["points"]["P1"]["max_lateral_displacement"].get<double>(),
              b["points"]["P1"]["max_lateral_displacement"].get<double>(), 1e-8);
  std::ifstream ca(plain / "history.csv"), cb(mirror / "history.csv");
  std::string la, lb;
  int rows = 0;
  while (std::getline(ca, la) && std::getline(cb, lb)) {
    if (rows++ == 0) {
      EXPECT_EQ(la, lb);  // the same header
      continue;
    }
    std::stringstream sa(la), sb(lb);
    std::string fa, fb;
    for (int field = 0; std::getline(sa, fa, ',') && std::getline(sb, fb, ','); ++field) {
      if (field < 2) continue;  // time and point name
      // 1e-7: history.csv prints u and v to 1e-9 of a metre, so a rounding apart reads as 1e-8.
      EXPECT_NEAR(std::stod(fa), std::stod(fb), 1e-7) << "row " << rows << ", field " << field;
    }
  }
  EXPECT_EQ(rows, 202);
  const CommandResult refused = ddafit("simulate " + kIncline + " --mirror --vtk-interval 0.1 --out " +
                                           (fs::path(DDAFIT_TEST_TMP) / "simulate_mirror" / "vtk").string(),
                                       "simulate_mirror");
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.err.find("--mirror"), std::string::npos) << refused.err;
  EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
}

TEST(Cli, MalformedSceneExitsTwoWithOneLine) {
  const fs::path scene = write_scene("bad_yaml", "time: {duration: 1, step: [\n");
  const CommandResult r = ddafit("simulate " + scene.string() + " --out /tmp/ddafit-never", "bad_yaml");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(scene.string()), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
}

TEST(Cli, NegativeStiffnessNamesTheKey) {
  std::string text = slurp(kIncline);
  const auto at = text.find("young_modulus: 5e+09");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 20, "young_modulus: -5e+09");
  const fs::path scene = write_scene("negative_e", text);
  const CommandResult r = ddafit("simulate " + scene.string() + " --quiet", "negative_e");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("young_modulus"), std::string::npos) << r.err;
}

TEST(Cli, FailedRunExitsThreeWithDiagnosis) {
  // A penalty far too soft, with no raises allowed: the slider sinks into the plane.
  std::string text = slurp(kIncline) + "control: {penalty: 1000, max_penalty_raises: 0}\n";
  const fs::path scene = write_scene("soft_penalty", text);
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "soft_penalty" / "out";
  const CommandResult r = ddafit("simulate " + scene.string() + " --out " + out.string() + " --quiet", "soft_penalty");
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("penetration"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("slider"), std::string::npos) << r.err;       // names the block
  EXPECT_NE(r.err.find("control.penalty"), std::string::npos) << r.err;  // says what to change
  const std::string summary = slurp(out / "summary.json");
  EXPECT_NE(summary.find("\"failed\""), std::string::npos);
  EXPECT_EQ(summary.find("nan"), std::string::npos);
}

// Regression (found 2026-12-05, revision .12.05.9): the stack of cases/verification at one-second
// steps let its blocks through the ground before the clock ran and reported the run completed,
// the blocks in free fall. From revision .12.05.10 it stopped (exit 3) naming block b2 and the
// ground; since .12.06.2 a quiet start that turns a block (here as the stack falls) is done again
// at steps of 0.03 sqrt(L / |g|), 9.6 ms for these 1 m blocks, and the stack stands: exit 0, its
// top within 5 mm (measured 2.5 mm, the joints settling to the run's steps' depth).
TEST(Cli, AStackRunAtOneSecondStepsStandsOnItsGround) {
  const std::string stack = std::string(DDAFIT_CASES_DIR) + "/verification/stack.yaml";
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "stack_huge_step" / "out";
  const std::string settings = " --set time.step=1 --set time.integrator=substep --set time.substeps=1";
  const CommandResult r =
      ddafit("simulate " + stack + settings + " --out " + out.string() + " --quiet", "stack_huge_step");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["status"].get<std::string>(), "completed");
  EXPECT_LT(j["points"]["top"]["max_total_displacement"].get<double>(), 0.005);
}

TEST(Cli, ShortTimeStepIsWarnedAbout) {
  // 2e-7 s is 1.25e-4 of the 2.1 m block's elastic period (1.6 ms), under the warning's 3e-4: shorter
  // than any step the implicit solver's accuracy was checked at (docs/theory.md, Known limits (a)),
  // so the run must say so rather than pass silently.
  std::string text = slurp(kIncline);
  const auto at = text.find("step: 0.001");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 11, "step: 0.0000002");
  text.replace(text.find("duration: 2"), 11, "duration: 0.0002");
  const fs::path scene = write_scene("short_step", text);
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "short_step" / "out";
  const CommandResult r = ddafit("simulate " + scene.string() + " --out " + out.string(), "short_step");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: time.step"), std::string::npos) << r.err;
  // --quiet prints errors only: the warning is then in summary.json alone.
  const CommandResult quiet = ddafit("simulate " + scene.string() + " --out " + out.string() + " --quiet", "short_step_quiet");
  EXPECT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_EQ(j["warnings"].size(), 1u);
}

TEST(Cli, UnknownOptionExitsTwo) {
  const CommandResult r = ddafit("simulate --no-such-flag", "bad_flag");
  EXPECT_EQ(r.code, 2);
}

TEST(Cli, BenchWritesOneCsvRowPerSize) {
  // Contract of `ddafit bench`: one row per block size with the run's counters. Section I
  // for 0.02 s keeps it to a second; a run that moves at all takes steps and passes.
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "bench" / "out";
  const std::string vajont = std::string(DDAFIT_CASES_DIR) + "/vajont/vajont.yaml";
  const CommandResult r = ddafit("bench " + vajont + " --sizes 34.3 --duration 0.02 --out " + out.string(), "bench");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream csv(slurp(out / "bench.csv"));
  std::string header, row, extra;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_FALSE(std::getline(csv, extra) && !extra.empty()) << "one size, one row";
  EXPECT_EQ(header.rfind("block_size,blocks,steps,open_close_iterations,", 0), 0u) << header;
  // The implicit solver's two ways of solving a pass: factorisations and factor updates.
  EXPECT_NE(header.find(",factorizations,factor_updates,"), std::string::npos) << header;
  EXPECT_EQ(row.rfind("34.3,183,", 0), 0u) << "section I has 183 free blocks: " << row;
  EXPECT_NE(row.find(",completed"), std::string::npos) << row;
}

TEST(Cli, BenchRefusesANonPositiveDuration) {
  const std::string vajont = std::string(DDAFIT_CASES_DIR) + "/vajont/vajont.yaml";
  const CommandResult r = ddafit("bench " + vajont + " --duration 0", "bench_bad");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--duration"), std::string::npos) << r.err;
}

TEST(Cli, VerifyPrintsRowsAndPasses) {
  const CommandResult r = ddafit("verify --only thrown", "verify_thrown");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 passed, 0 failed"), std::string::npos) << r.out;
}

TEST(Cli, AnimateDrawsEverySnapshotAndTheChosenTimes) {
  // Contract of `ddafit animate`: one PNG per VTK snapshot, the chosen times as their own
  // PNGs, and an animated GIF. The incline for 1 s with a snapshot every 0.25 s gives 5
  // snapshots (t = 0, 0.25, ..., 1); PNG and GIF files are checked by their signatures.
  const fs::path run = fs::path(DDAFIT_TEST_TMP) / "animate" / "run";
  fs::remove_all(run);
  const CommandResult sim = ddafit("simulate " + kIncline + " --set time.duration=1 --vtk-interval 0.25 --quiet --out " +
                                       run.string(), "animate_sim");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const CommandResult r = ddafit("animate " + run.string() + " --times 0.5,1", "animate");
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path out = run / "animation";
  for (int k = 0; k < 5; ++k) {
    const fs::path frame = out / ("frame_0000" + std::to_string(k) + ".png");
    EXPECT_EQ(slurp(frame).substr(1, 3), "PNG") << frame;
  }
  EXPECT_FALSE(fs::exists(out / "frame_00005.png")) << "5 snapshots, 5 frames";
  EXPECT_EQ(slurp(out / "speed_t000.5s.png").substr(1, 3), "PNG");
  EXPECT_EQ(slurp(out / "speed_t001.0s.png").substr(1, 3), "PNG");
  EXPECT_EQ(slurp(out / "animation.gif").substr(0, 6), "GIF89a");
}

TEST(Cli, AnimateRefusesARunWithoutSnapshotsOrABrokenOne) {
  // No vtk folder: exit 2, saying how to make one.
  const fs::path empty = fs::path(DDAFIT_TEST_TMP) / "animate_none";
  fs::create_directories(empty);
  const CommandResult none = ddafit("animate " + empty.string(), "animate_none");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--vtk-interval"), std::string::npos) << none.err;
  // A snapshot cut short: exit 2 naming the file and the line.
  const fs::path broken = fs::path(DDAFIT_TEST_TMP) / "animate_broken";
  fs::create_directories(broken / "vtk");
  std::ofstream(broken / "vtk" / "blocks_00000.vtk")
      << "# vtk DataFile Version 3.0\nddafit state t=0 s\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0\n1 0 0\n";
  const CommandResult cut = ddafit("animate " + broken.string(), "animate_broken");
  EXPECT_EQ(cut.code, 2);
  EXPECT_NE(cut.err.find("blocks_00000.vtk: line"), std::string::npos) << cut.err;
  EXPECT_EQ(std::count(cut.err.begin(), cut.err.end(), '\n'), 1) << cut.err;
  // A time outside the snapshots (two hand-written ones, t = 0 and 1 s): exit 2 naming --times.
  const fs::path two = fs::path(DDAFIT_TEST_TMP) / "animate_late";
  fs::create_directories(two / "vtk");
  for (int k = 0; k < 2; ++k)
    std::ofstream(two / "vtk" / ("blocks_0000" + std::to_string(k) + ".vtk"))
        << "# vtk DataFile Version 3.0\nddafit state t=" << k
        << " s\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n0 0 0\n1 0 0\n0 1 0\nPOLYGONS 1 4\n3 0 1 2\n"
           "CELL_DATA 1\nSCALARS fixed int 1\nLOOKUP_TABLE default\n0\nSCALARS speed double 1\nLOOKUP_TABLE default\n1\n";
  const CommandResult late = ddafit("animate " + two.string() + " --times 7", "animate_late");
  EXPECT_EQ(late.code, 2);
  EXPECT_NE(late.err.find("--times"), std::string::npos) << late.err;
}

}  // namespace
