// `ddafit invert` as a user runs it: one-line errors with exit code 2 for bad studies,
// --check on the Vajont study, and a real inversion killed with SIGKILL and resumed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;

const std::string kCases = DDAFIT_CASES_DIR;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CommandResult {
  int code = -1;
  std::string out, err;
};

CommandResult ddafit(const std::string& args, const fs::path& dir) {
  fs::create_directories(dir);
  const std::string cmd = std::string(DDAFIT_BINARY) + " " + args + " > " + (dir / "stdout").string() + " 2> " +
                          (dir / "stderr").string();
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir / "stdout"), slurp(dir / "stderr")};
}

fs::path fresh_dir(const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A valid study over the twin scene; each bad-study case replaces one piece of it.
const std::string kParameters =
    "  - {name: deg, key: interfaces.clay.degradation_percent, lower: 0, upper: 60, start: 10, resolution: 0.5}\n";
const std::string kObservations = "  - {point: A, quantity: max_total_displacement, value: 2.69, sigma: 0.01}\n";

std::string study_text(const std::string& parameters, const std::string& observations, const std::string& extra = "") {
  return "scene: " + kCases + "/inverse/two_sliders.yaml\nparameters:\n" + parameters + "observations:\n" +
         observations + extra;
}

struct BadStudy {
  const char* tag;
  std::string text;
  const char* key;  // the key the message must name
};

TEST(InvertCli, BadStudiesGetOneLineNamingTheKeyAndExitCode2) {
  const std::string p = "  - {name: deg, key: interfaces.clay.degradation_percent, ";
  const BadStudy cases[] = {
      {"unknown_key", study_text(p + "lowr: 0, upper: 60, start: 10, resolution: 0.5}\n", kObservations),
       "parameters[0].lowr"},
      {"impossible_bounds", study_text(p + "lower: 60, upper: 0, start: 10, resolution: 0.5}\n", kObservations),
       "parameters[0].upper"},
      {"equal_bounds", study_text(p + "lower: 5, upper: 5, start: 5, resolution: 0.5}\n", kObservations),
       "parameters[0].upper"},
      {"start_outside", study_text(p + "lower: 0, upper: 60, start: 70, resolution: 0.5}\n", kObservations),
       "parameters[0].start"},
      {"zero_resolution", study_text(p + "lower: 0, upper: 60, start: 10, resolution: 0}\n", kObservations),
       "parameters[0].resolution"},
      {"negative_sigma",
       study_text(kParameters, "  - {point: A, quantity: max_total_displacement, value: 2.69, sigma: -1}\n"),
       "observations[0].sigma"},
      {"unknown_point",
       study_text(kParameters, "  - {point: Z, quantity: max_total_displacement, value: 2.69, sigma: 0.01}\n"),
       "observations[0].point"},
      {"unknown_quantity", study_text(kParameters, "  - {point: A, quantity: runout, value: 2.69, sigma: 0.01}\n"),
       "observations[0].quantity"},
      {"unknown_algorithm", study_text(kParameters, kObservations, "method: {algorithm: LN_COBYLA}\n"),
       "method.algorithm"},
      {"scene_rejects_key",
       study_text("  - {name: d, key: interfaces.clay.degradatoin, lower: 0, upper: 1, start: 0.5, resolution: 0.1}\n",
                  kObservations),
       "parameters[0].key"},
      {"switch_as_parameter",
       study_text("  - {name: s, key: control.plane_strain, lower: 0, upper: 1, start: 0.5, resolution: 0.1}\n",
                  kObservations),
       "parameters[0].key"},
      {"interface_not_in_scene",
       study_text("  - {name: s, key: interfaces.sand.friction_angle, lower: 5, upper: 30, start: 20, resolution: 1}\n",
                  kObservations),
       "parameters[0].key"},
      {"two_forms_of_one_roughness",
       study_text(p + "lower: 0, upper: 60, start: 10, resolution: 0.5}\n"
                      "  - {name: i, key: interfaces.clay.roughness_angle, lower: 0, upper: 9, start: 2, resolution: 0.5}\n",
                  kObservations),
       "parameters[1].key"},
  };
  for (const BadStudy& c : cases) {
    const fs::path dir = fresh_dir(std::string("invert_bad/") + c.tag);
    std::ofstream(dir / "study.yaml") << c.text;
    const CommandResult r = ddafit("invert " + (dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
    EXPECT_EQ(r.code, 2) << c.tag << ": " << r.err;
    // One line, "FILE: KEY: PROBLEM": the file first, then the key the user must fix.
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << c.tag << ": " << r.err;
    EXPECT_EQ(r.err.rfind((dir / "study.yaml").string() + ": " + c.key, 0), 0u) << c.tag << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "evaluations.sqlite")) << c.tag << ": nothing may run";
  }
}

TEST(InvertCli, CheckValidatesTheVajontStudyWithoutRunning) {
  const fs::path dir = fresh_dir("invert_check");
  const CommandResult r = ddafit("invert " + kCases + "/vajont/study.yaml --check --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // The plan names the three block-size levels and all three Hendron & Patton targets.
  EXPECT_NE(r.out.find("levels 34.3, 23.1, 16"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("duration <= 45"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max_lateral_displacement = 450"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "out")) << "--check runs nothing and writes nothing";
}

TEST(InvertCli, ScanTabulatesChi2AndReusesItsCacheOnResume) {
  const fs::path dir = fresh_dir("scan");
  const std::string args = "scan " + kCases + "/inverse/twin_study.yaml --parameter joint_roughness --points 3 --out " +
                           (dir / "out").string();
  const CommandResult first = ddafit(args, dir / "1");
  ASSERT_EQ(first.code, 0) << first.err;
  std::ifstream csv(dir / "out" / "scan.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 4);  // header + 0, 6, 12 deg
  const CommandResult again = ddafit(args + " --resume", dir / "2");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("0 run, 3 cached"), std::string::npos) << again.err;
}

long cached_rows(const fs::path& db) {
  sqlite3* h = nullptr;
  long n = -1;
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_busy_timeout(h, 1000);
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(h, "SELECT COUNT(*) FROM evaluations", -1, &s, nullptr) == SQLITE_OK &&
        sqlite3_step(s) == SQLITE_ROW)
      n = sqlite3_column_int64(s, 0);
    sqlite3_finalize(s);
  }
  sqlite3_close(h);
  return n;
}

// The twin study with a 0.2 ms time step: about 0.15 s per forward run, slow enough to
// kill the inversion part-way.
fs::path slow_twin_study(const fs::path& dir) {
  std::string text = slurp(kCases + "/inverse/twin_study.yaml");
  text.replace(text.find("scene: two_sliders.yaml"), 23,
               "scene: " + kCases + "/inverse/two_sliders.yaml\nsettings: {time.step: 0.0002}");
  const fs::path p = dir / "study.yaml";
  std::ofstream(p) << text;
  return p;
}

TEST(InvertCli, KilledInversionResumesFromTheCacheToTheSameBestPoint) {
  constexpr long kKillAfter = 12;  // evaluations in the cache before SIGKILL
  const fs::path dir = fresh_dir("invert_resume");
  const fs::path study = slow_twin_study(dir);
  const fs::path out = dir / "killed", db = out / "evaluations.sqlite";

  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string log = (dir / "killed.log").string();
    if (!std::freopen(log.c_str(), "w", stderr) || !std::freopen("/dev/null", "w", stdout)) _exit(127);
    execl(DDAFIT_BINARY, DDAFIT_BINARY, "invert", study.c_str(), "--out", out.c_str(), "--quiet", nullptr);
    _exit(127);
  }
  long before_kill = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(db) && (before_kill = cached_rows(db)) >= kKillAfter) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the inversion finished before it could be killed";
  const long kept = cached_rows(db);
  // Every evaluation committed before the kill is still there (at most the run in flight is lost).
  EXPECT_GE(kept, before_kill);

  const CommandResult resumed = ddafit("invert " + study.string() + " --out " + out.string() + " --resume --quiet", dir / "r");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  const CommandResult again = ddafit("invert " + study.string() + " --out " + out.string() + " --quiet", dir / "a");
  EXPECT_EQ(again.code, 2) << "an existing cache without --resume is refused: " << again.err;
  const fs::path fresh = dir / "uninterrupted";
  const CommandResult whole = ddafit("invert " + study.string() + " --out " + fresh.string() + " --quiet", dir / "u");
  ASSERT_EQ(whole.code, 0) << whole.err;

  const auto r = nlohmann::json::parse(slurp(out / "report.json"));
  const auto u = nlohmann::json::parse(slurp(fresh / "report.json"));
  // The resumed run replays the kept evaluations instead of running them again ...
  EXPECT_EQ(r["evaluations_cached"].get<long>(), kept);
  EXPECT_EQ(r["evaluations_run"].get<long>() + kept, r["evaluations_total"].get<long>());
  // ... and, the forward model being deterministic and the cache bit-exact, follows the
  // same path as an uninterrupted run: same number of evaluations, same best point
  // (compared exactly: any difference would mean the cache changed a value).
  EXPECT_EQ(r["evaluations_total"], u["evaluations_total"]);
  EXPECT_EQ(u["evaluations_cached"].get<long>(), 0);
  EXPECT_EQ(r["best"], u["best"]);
  EXPECT_EQ(r["chi2"], u["chi2"]);
  std::printf("[resume] killed after %ld cached evaluations (%ld kept); resumed: %ld run + %ld cached = %ld; "
              "uninterrupted: %ld run\n",
              before_kill, kept, r["evaluations_run"].get<long>(), r["evaluations_cached"].get<long>(),
              r["evaluations_total"].get<long>(), u["evaluations_run"].get<long>());
}

}  // namespace
