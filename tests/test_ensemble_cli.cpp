// `ddafit simulate --ensemble` from the command line: its evaluation cache (a resumed or
// enlarged ensemble runs only the realisations it lacks, and gives the numbers a fresh one
// gives), and the same ensemble under a real mpirun (three ranks on the two cores). A
// study's measured model spread (model_sigma: ensemble) also runs on the MPI ranks of a
// scan and measures the same sigma as on threads.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_run.hpp"

namespace {

using namespace ddafit_test;

const std::string kCollision = std::string(DDAFIT_CASES_DIR) + "/verification/collision.yaml";
const std::string kMpirun =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_warn_on_fork=0 mpirun -n 3 --oversubscribe ";

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The lines of ensemble.csv: one per realisation and point, every quantity to 12 digits.
std::string members(const fs::path& dir) { return slurp(dir / "ensemble.csv"); }

TEST(EnsembleCli, AResumedEnsembleRunsOnlyTheRealisationsItLacksAndGivesTheFreshNumbers) {
  const fs::path root = fs::path(DDAFIT_TEST_TMP) / "ensemble_cache";
  fs::remove_all(root);
  const std::string base = "simulate " + kCollision + " --ensemble ";
  ASSERT_EQ(ddafit(base + "5 --out " + (root / "fresh").string(), "ensemble_cache/a").code, 0);
  ASSERT_EQ(ddafit(base + "3 --out " + (root / "grown").string(), "ensemble_cache/b").code, 0);
  // The same folder again without --resume: refused in one line naming the cache file.
  const CommandResult again = ddafit(base + "3 --out " + (root / "grown").string(), "ensemble_cache/c");
  EXPECT_EQ(again.code, 2);
  EXPECT_NE(again.err.find("evaluations.sqlite: holds 3 realisations"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;
  // Enlarged to 5 with --resume: realisations 3 and 4 run, 0-2 come from the cache.
  const CommandResult grown = ddafit(base + "5 --resume --out " + (root / "grown").string(), "ensemble_cache/d");
  ASSERT_EQ(grown.code, 0) << grown.err;
  EXPECT_NE(grown.err.find("3 of 5 realisations from"), std::string::npos) << grown.err;
  EXPECT_EQ(grown.err.find("realisation   1:"), std::string::npos) << "realisation 1 ran again:\n" << grown.err;
  EXPECT_NE(grown.err.find("realisation   4:"), std::string::npos) << grown.err;
  // Cached numbers are the runs' own, to the last digit the files carry, and the members
  // differ (the collision spreads: the check would pass on copies of one run otherwise).
  EXPECT_EQ(members(root / "grown"), members(root / "fresh"));
  EXPECT_EQ(slurp(root / "grown" / "history.csv"), slurp(root / "fresh" / "history.csv"));
  const std::string csv = members(root / "fresh");
  std::smatch m0, m1;
  ASSERT_TRUE(std::regex_search(csv, m0, std::regex("\n0,completed,target,([^,]+)")));
  ASSERT_TRUE(std::regex_search(csv, m1, std::regex("\n1,completed,target,([^,]+)")));
  EXPECT_NE(m0[1].str(), m1[1].str());
  // All of them cached: nothing runs.
  const CommandResult cached = ddafit(base + "5 --resume --out " + (root / "grown").string(), "ensemble_cache/f");
  ASSERT_EQ(cached.code, 0) << cached.err;
  EXPECT_NE(cached.err.find("5 of 5 realisations from"), std::string::npos) << cached.err;
  EXPECT_EQ(cached.err.find("realisation   "), std::string::npos) << "a cached realisation ran again:\n" << cached.err;
  EXPECT_EQ(members(root / "grown"), members(root / "fresh"));
  // A changed scene is a different key: nothing is reused, and nothing is refused.
  const CommandResult changed =
      ddafit(base + "2 --set time.duration=0.4 --out " + (root / "grown").string(), "ensemble_cache/e");
  EXPECT_EQ(changed.code, 0) << changed.err;
  EXPECT_EQ(changed.err.find("realisations from"), std::string::npos) << changed.err;
}

TEST(EnsembleCli, MpirunGivesTheSameMembersAsThreads) {
  const fs::path root = fs::path(DDAFIT_TEST_TMP) / "ensemble_mpi";
  fs::remove_all(root);
  fs::create_directories(root);
  const std::string run = std::string(DDAFIT_BINARY) + " simulate " + kCollision + " --ensemble 6";
  ASSERT_EQ(shell(run + " --jobs 2 --out " + (root / "local").string() + " > /dev/null 2>&1"), 0);
  ASSERT_EQ(shell(kMpirun + run + " --out " + (root / "mpi").string() + " > " + (root / "mpi.log").string() + " 2>&1"), 0)
      << slurp(root / "mpi.log");
  EXPECT_EQ(slurp(root / "mpi.log").find("rank 0 runs this command alone"), std::string::npos);
  EXPECT_EQ(members(root / "mpi"), members(root / "local"));
  EXPECT_EQ(slurp(root / "mpi" / "history.csv"), slurp(root / "local" / "history.csv"));
}

// The "model_sigma = ..." notes of a scan's model spread.
std::vector<std::string> spread_notes(const std::string& log) {
  std::vector<std::string> out;
  const std::regex note("model_sigma = [^;]+");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), note); it != std::sregex_iterator(); ++it)
    out.push_back(it->str());
  return out;
}

// The "model spread: realisation" lines of a log.
std::vector<std::string> spread_lines(const std::string& log) {
  std::vector<std::string> out;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);)
    if (line.find("model spread: realisation") != std::string::npos) out.push_back(line);
  return out;
}

TEST(EnsembleCli, AScanMeasuresTheSameModelSpreadOnMpiRanksAsOnThreads) {
  const fs::path root = fs::path(DDAFIT_TEST_TMP) / "spread_mpi";
  fs::remove_all(root);
  fs::create_directories(root);
  // The twin study with its first observation's model sigma measured by 4 realisations.
  std::string study = slurp(fs::path(DDAFIT_CASES_DIR) / "inverse" / "twin_study.yaml");
  const std::string first = "value: 2.6943, sigma: 0.01}";
  ASSERT_NE(study.find(first), std::string::npos);
  study.replace(study.find(first), first.size(), "value: 2.6943, sigma: 0.01, model_sigma: ensemble}");
  study.replace(study.find("scene: two_sliders.yaml"), 23,
                "scene: " + (fs::path(DDAFIT_CASES_DIR) / "inverse" / "two_sliders.yaml").string());
  std::ofstream(root / "study.yaml") << study << "ensemble: 4\n";
  const std::string scan = std::string(DDAFIT_BINARY) + " scan " + (root / "study.yaml").string() +
                           " --design lhs --samples 2 --seed 3";
  ASSERT_EQ(shell(scan + " --out " + (root / "local").string() + " > " + (root / "local.log").string() + " 2>&1"), 0)
      << slurp(root / "local.log");
  ASSERT_EQ(shell(kMpirun + scan + " --out " + (root / "mpi").string() + " > " + (root / "mpi.log").string() + " 2>&1"), 0)
      << slurp(root / "mpi.log");
  const std::vector<std::string> local = spread_notes(slurp(root / "local.log"));
  ASSERT_EQ(local.size(), 1u) << slurp(root / "local.log");
  EXPECT_EQ(spread_notes(slurp(root / "mpi.log")), local);
  // All four realisations ran on the worker ranks and came back completed.
  const std::string log = slurp(root / "mpi.log");
  for (int k = 1; k < 4; ++k)
    EXPECT_NE(log.find("realisation " + std::to_string(k) + " of 4 completed in"), std::string::npos) << log;
  const std::vector<std::string> lines = spread_lines(log);
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(),
                          [](const std::string& l) { return l.find("on a worker rank") != std::string::npos; }),
            4)
      << log;
}

}  // namespace

namespace {

TEST(EnsembleCli, JobArrayFlagsWithoutAnEnsembleOrWithABadTaskAreRefusedInOneLine) {
  const fs::path root = fs::path(DDAFIT_TEST_TMP) / "ensemble_job_refusals";
  fs::remove_all(root);
  const CommandResult plain = ddafit("simulate " + kCollision + " --slurm " + (root / "job").string(), "ensemble_job_refusals/a");
  EXPECT_EQ(plain.code, 2);
  EXPECT_NE(plain.err.find("belong to --ensemble K"), std::string::npos) << plain.err;
  // A job folder for 3 realisations; a task index past its end, and a folder of another K.
  ASSERT_EQ(ddafit("simulate " + kCollision + " --ensemble 3 --slurm " + (root / "job").string() + " --out " +
                       (root / "out").string(),
                   "ensemble_job_refusals/b")
                .code,
            0);
  const CommandResult past = ddafit("simulate " + kCollision + " --ensemble 3 --task " + (root / "job").string() +
                                        " --task-index 3",
                                    "ensemble_job_refusals/c");
  EXPECT_EQ(past.code, 2);
  EXPECT_NE(past.err.find("points.txt: --task-index 3: no such realisation (it has 3)"), std::string::npos) << past.err;
  const CommandResult other = ddafit("simulate " + kCollision + " --ensemble 2 --task " + (root / "job").string() +
                                         " --task-index 2",
                                     "ensemble_job_refusals/d");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("line 3: not a realisation of this --ensemble 2"), std::string::npos) << other.err;
  EXPECT_FALSE(fs::exists(root / "job" / "results" / "2.json"));
}

}  // namespace
