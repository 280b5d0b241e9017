// `ddafit scan` from the command line: designs, the plan, and the same scan under a real
// mpirun (three ranks on the two cores, --oversubscribe), whose chi2 must equal the local
// run's at every point. A forward run that hangs is killed and recorded as failed without
// taking the job down.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli_run.hpp"

namespace {

using namespace ddafit_test;

const std::string kStudy = std::string(DDAFIT_CASES_DIR) + "/inverse/twin_study.yaml";

// Column `column` (0-based) of every data row of a CSV.
std::vector<std::string> csv_column(const fs::path& path, int column) {
  std::ifstream in(path);
  std::vector<std::string> out;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    size_t start = 0;
    for (int c = 0; c < column; ++c) start = line.find(',', start) + 1;
    out.push_back(line.substr(start, line.find(',', start) - start));
  }
  return out;
}

// mpirun as root needs these (tests run as root in CI); no fork warnings from the workers'
// child processes.
const std::string kMpirun =
    "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_warn_on_fork=0 mpirun -n 3 --oversubscribe ";

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ScanCli, DryRunPrintsThePlanAndRunsNothing) {
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "scan_dry" / "out";
  fs::remove_all(out);
  const CommandResult r = ddafit("scan " + kStudy + " --design grid --points 3 --dry-run --out " + out.string(), "scan_dry");
  ASSERT_EQ(r.code, 0) << r.err;
  // 3 x 3 grid over two parameters, crossed with the study's two critical-distance levels.
  EXPECT_NE(r.out.find("18 runs"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "evaluations.sqlite"));
}

TEST(ScanCli, MpirunGivesTheSameChi2PerPointAsTheLocalRun) {
  const fs::path local = fs::path(DDAFIT_TEST_TMP) / "scan_mpi" / "local";
  const fs::path mpi = fs::path(DDAFIT_TEST_TMP) / "scan_mpi" / "mpi";
  fs::remove_all(local.parent_path());
  const std::string scan = std::string(DDAFIT_BINARY) + " scan " + kStudy + " --design lhs --samples 8 --seed 5";
  ASSERT_EQ(shell(scan + " --jobs 2 --out " + local.string() + " > /dev/null 2>&1"), 0);
  ASSERT_EQ(shell(kMpirun + scan + " --out " + mpi.string() + " > " + (local.parent_path() / "mpi.log").string() + " 2>&1"), 0)
      << slurp(local.parent_path() / "mpi.log");
  const auto chi2_local = csv_column(local / "runs.csv", 4), chi2_mpi = csv_column(mpi / "runs.csv", 4);
  ASSERT_EQ(chi2_local.size(), 16u);  // 8 samples x 2 levels
  EXPECT_EQ(chi2_local, chi2_mpi);    // printed to 6 digits from bit-identical runs
  EXPECT_EQ(csv_column(local / "runs.csv", 1), csv_column(mpi / "runs.csv", 1));  // same points
}

TEST(ScanCli, AHungRunUnderMpirunIsKilledAndRecordedAsFailed) {
  // The twin scene made to run for 500 simulated seconds: each run takes far longer than
  // the 1 s allowed, so every run must be killed (twice: one retry) and recorded as failed,
  // and the job must still finish with its runs.csv.
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / "scan_hang";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(std::string(DDAFIT_CASES_DIR) + "/inverse/two_sliders.yaml", dir / "two_sliders.yaml");
  std::string study = slurp(kStudy);
  study.replace(study.find("profile:"), 0, "settings: {time.duration: 500}\n");
  std::ofstream(dir / "study.yaml") << study;
  const std::string scan = std::string(DDAFIT_BINARY) + " scan " + (dir / "study.yaml").string() +
                           " --design lhs --samples 2 --run-timeout 1 --out " + (dir / "out").string();
  ASSERT_EQ(shell(kMpirun + scan + " > " + (dir / "log").string() + " 2>&1"), 0) << slurp(dir / "log");
  const auto status = csv_column(dir / "out" / "runs.csv", 5);
  ASSERT_EQ(status.size(), 4u);
  for (const std::string& s : status) EXPECT_EQ(s, "failed");
  EXPECT_NE(slurp(dir / "log").find("hung past 1 s"), std::string::npos) << slurp(dir / "log");
}

}  // namespace
