// Bad input never crashes: every class of input that once broke ddafit (fuzzing and a new
// user's attempts, issue "Bad input never crashes ...") ends as exit 2 with one line naming
// the file, the key and the problem; never a signal, a hang or an exit 0 on unused input.
// Long runs stop cleanly on SIGINT and SIGTERM.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli_run.hpp"

namespace {

using namespace ddafit_test;

const std::string kCases = DDAFIT_CASES_DIR;
const std::string kIncline = kCases + "/verification/incline_i5.yaml";

// A region scene like Vajont's, small: one slide region cut by vertical joints over a
// fixed bedrock, reading the Vajont CSV polylines.
std::string region_scene(const std::string& slide_extra, const std::string& joint = "{dip: 90, spacing_ratio: 1.15}") {
  const std::string v = kCases + "/vajont/";
  return "time: {duration: 0.1, step: 0.005}\n"
         "materials: {rock: {density: 2500, young_modulus: 5.0e9, poisson_ratio: 0.25}}\n"
         "interfaces: {joint: {friction_angle: 40}}\n"
         "mesh: {block_size: 200}\n"
         "regions:\n"
         "  - {name: slide, material: rock" + slide_extra + ", between: {upper: " + v + "ground_before.csv, lower: " + v +
         "basal_surface.csv, x_min: 0, x_max: 1408.9}, joint_sets: [" + joint + "]}\n"
         "  - {name: bedrock, material: rock, fixed: true, below: {surface: " + v + "bedrock_surface.csv, base: 400}}\n";
}

// The contract for bad input: exit 2, no signal, one line that names `key`.
void expect_refused(const CommandResult& r, const std::string& key) {
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(key), std::string::npos) << "message does not name " << key << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Found 2026-11-26: `--set interfaces.nope.friction_angle=3` ran (exit 0), adding an
// interface no block used and leaving the one meant unchanged.
TEST(BadInput, SetNamesAnExistingMaterialOrInterface) {
  for (const std::string key : {"interfaces.nope.friction_angle", "materials.granite.density"}) {
    const CommandResult r = ddafit("simulate " + kIncline + " --set " + key + "=3 --out " +
                                       (fs::path(DDAFIT_TEST_TMP) / "set_unknown_entry" / "out").string(),
                                   "set_unknown_entry");
    expect_refused(r, key);
    EXPECT_NE(r.err.find("(it has: "), std::string::npos) << r.err;
  }
}

TEST(BadInput, MeshLengthsMustBeFiniteAndSized) {
  // Infinite or 1e308 spacings and block sizes reached the mesher (SIGFPE; "1 vertices" on
  // blocks the user never wrote); 1e-300 printed "-9223372036854775808 blocks".
  struct Case { std::string tag, scene, key; };
  const std::vector<Case> cases = {
      {"mesh_inf_size", region_scene(", block_size: .inf"), "regions[0].block_size"},
      {"mesh_huge_size", region_scene(", block_size: 1e308"), "regions[0].block_size"},
      {"mesh_negative_size", region_scene(", block_size: -5"), "regions[0].block_size"},
      {"mesh_nan_size", region_scene(", block_size: .nan"), "regions[0].block_size"},
      {"mesh_inf_spacing", region_scene("", "{dip: 90, spacing: .inf}"), "regions[0].joint_sets[0].spacing"},
      {"mesh_huge_spacing", region_scene("", "{dip: 90, spacing: 1e308}"), "regions[0].joint_sets[0].spacing"},
      {"mesh_huge_x", region_scene("").replace(region_scene("").find("x_max: 1408.9"), 13, "x_max: .inf"),
       "regions[0].between.x_max"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.tag);
    const fs::path scene = write_scene(c.tag, c.scene);
    expect_refused(ddafit("mesh " + scene.string() + " --out " + (scene.parent_path() / "out").string(), c.tag), c.key);
  }
  const fs::path scene = write_scene("mesh_tiny_spacing", region_scene("", "{dip: 90, spacing: 1e-300}"));
  const CommandResult r = ddafit("mesh " + scene.string() + " --out " + (scene.parent_path() / "out").string(), "mesh_tiny_spacing");
  expect_refused(r, "regions[0]");
  EXPECT_EQ(r.err.find("-9223372036854775808"), std::string::npos) << r.err;
}

TEST(BadInput, NamesMustBeValidUtf8) {
  // An invalid byte in a region name aborted `mesh` in the JSON writer.
  const fs::path scene = write_scene("utf8_name", region_scene("").replace(region_scene("").find("name: slide"), 11,
                                                                         "name: \"sl\xff" "ide\""));
  expect_refused(ddafit("mesh " + scene.string() + " --out " + (scene.parent_path() / "out").string(), "utf8_name"),
                 "regions[0].name");
}

TEST(BadInput, AnOutputFolderThatCannotBeWrittenIsNamed) {
  // --out through a regular file cannot be created, whoever runs the tests (root ignores
  // permissions); `mesh`, `plot`, `bench` and `stable` once aborted or exited 0 on it.
  const fs::path file = write_file("out_file", "a_file", "not a folder\n");
  const std::string out = " --out " + (file / "sub").string();
  expect_refused(ddafit("simulate " + kIncline + out, "out_file_simulate"), "--out");
  const fs::path scene = write_scene("out_file_mesh", region_scene(""));
  expect_refused(ddafit("mesh " + scene.string() + out, "out_file_mesh"), "--out");
  expect_refused(ddafit("stable " + kIncline + " --interface interface --time 0.1" + out, "out_file_stable"), "--out");
  const std::string study = kCases + "/inverse/twin_study.yaml";
  expect_refused(ddafit("invert " + study + out, "out_file_invert"), "--out");
  expect_refused(ddafit("scan " + study + " --parameter basal_degradation --points 2" + out, "out_file_scan"), "--out");
}

TEST(BadInput, OneYamlDocumentPerFile) {
  // A `---` line dropped everything after it with exit 0.
  const fs::path scene = write_scene("two_documents", slurp(kIncline) + "---\ntime: {duration: 99}\n");
  expect_refused(ddafit("simulate " + scene.string() + " --out " + (scene.parent_path() / "out").string(), "two_documents"),
                 "more than one YAML document");
  const std::string study = slurp(kCases + "/inverse/twin_study.yaml");
  const fs::path study_file = write_file("two_study_documents", "study.yaml", "---\n" + study + "---\nmethod: {budget: 1}\n");
  expect_refused(ddafit("invert " + study_file.string() + " --check", "two_study_documents"), "more than one YAML document");
}

TEST(BadInput, InputsMustBeRegularFilesOfBoundedSize) {
  // `simulate /dev/zero` read until memory ran out.
  expect_refused(ddafit("simulate /dev/zero --out " + (fs::path(DDAFIT_TEST_TMP) / "dev_zero").string(), "dev_zero"),
                 "not a regular file");
  expect_refused(ddafit("simulate " + kCases + " --out " + (fs::path(DDAFIT_TEST_TMP) / "a_folder").string(), "a_folder"),
                 "not a regular file");
  // 65 MB of sparse file: over the 64 MB limit without writing 65 MB.
  const fs::path big = write_file("big_input", "big.yaml", "time: {duration: 1}\n");
  fs::resize_file(big, (65ull << 20));
  expect_refused(ddafit("simulate " + big.string() + " --out " + (big.parent_path() / "out").string(), "big_input"),
                 "inputs are limited to 64 MB");
}

TEST(BadInput, RunsThatCouldNotEndAreRefused) {
  // output.interval 1e-14 stalled at 0 % forever; a step of 1e-300 s ran without end.
  const std::string out = " --out " + (fs::path(DDAFIT_TEST_TMP) / "endless").string() + " --quiet";
  expect_refused(ddafit("simulate " + kIncline + " --set output.interval=1e-14" + out, "endless_interval"), "output.interval");
  expect_refused(ddafit("simulate " + kIncline + " --set time.step=1e-300" + out, "endless_step"), "time.step");
  expect_refused(ddafit("simulate " + kIncline + " --set time.duration=1e300" + out, "endless_duration"), "time.step");
}

TEST(BadInput, StudyNumbersAreCheckedBeforeAnyRun) {
  // NaN, infinite or 1e308 values, denormal sigmas and resolutions passed --check and made
  // `invert` segfault after Ceres reported an error.
  const std::string study = slurp(kCases + "/inverse/twin_study.yaml");
  struct Case { std::string tag, from, to, key; };
  const std::vector<Case> cases = {
      {"obs_nan", "value: 2.6943", "value: .nan", "observations[0].value"},
      {"obs_huge", "value: 2.6943", "value: 1e308", "observations[0].value"},
      {"sigma_denormal", "sigma: 0.01}", "sigma: 1e-310}", "observations[0].sigma"},
      {"bound_inf", "upper: 60", "upper: .inf", "parameters[0].upper"},
      {"resolution_denormal", "resolution: 0.5", "resolution: 1e-310", "parameters[0].resolution"},
      {"scene_name_long", "scene: two_sliders.yaml", "scene: " + std::string(300, 'a') + ".yaml", "scene"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.tag);
    std::string text = study;
    text.replace(text.find(c.from), c.from.size(), c.to);
    const fs::path file = write_file(c.tag, "study.yaml", text);
    fs::copy_file(kCases + "/inverse/two_sliders.yaml", file.parent_path() / "two_sliders.yaml",
                  fs::copy_options::overwrite_existing);
    expect_refused(ddafit("invert " + file.string() + " --check", c.tag), c.key);
  }
}

TEST(BadInput, SetAppliesToTheBuiltInScene) {
  // `simulate --set` without a scene ignored every --set with exit 0.
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "builtin_set" / "out";
  const CommandResult r = ddafit("simulate --set time.duration=0.5 --out " + out.string() + " --quiet", "builtin_set");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
  EXPECT_NEAR(summary["run"]["simulated_time"].get<double>(), 0.5, 1e-9);  // the run ends where --set says
  expect_refused(ddafit("simulate --set time.durration=0.5 --out " + out.string(), "builtin_set_typo"), "time.durration");
}

TEST(BadInput, PlotRefusesAnotherScenesHistory) {
  // `plot` with another scene picked rows by position and drew mislabelled curves.
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "plot_other" / "run";
  ASSERT_EQ(ddafit("simulate " + kIncline + " --set time.duration=0.05 --out " + out.string() + " --quiet", "plot_other_run").code, 0);
  expect_refused(ddafit("plot " + kCases + "/inverse/two_sliders.yaml " + out.string(), "plot_other"), "history.csv");
}

TEST(BadInput, PlotDrawsAnEstimateAndRefusesAnEmptyRange) {
  // The lateral speed-distance chart (seed Fig. 14) with a field estimate as bands; a
  // range given high-to-low would draw an empty band, so it is refused.
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "plot_bands" / "run";
  ASSERT_EQ(ddafit("simulate " + kIncline + " --set time.duration=0.05 --out " + out.string() + " --quiet", "plot_bands_run").code, 0);
  expect_refused(ddafit("plot " + kIncline + " " + out.string() + " --runout-range 500 400", "plot_bands_reversed"),
                 "--runout-range");
  const CommandResult r = ddafit("plot " + kIncline + " " + out.string() +
                                     " --runout-range 400 500 --speed-range 20 25 --estimate 'Hendron & Patton'",
                                 "plot_bands");
  if (r.code == 3) GTEST_SKIP() << "gnuplot missing: " << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(out / "velocity_distance_lateral.png").substr(1, 3), "PNG");
  const std::string script = slurp(out / "history.gp");
  EXPECT_NE(script.find("Hendron & Patton: runout 400-500 m"), std::string::npos) << "the band is in the legend";
  EXPECT_NE(script.find("first 20 to graph 1, first 25"), std::string::npos) << "the speed band spans 20-25 m/s";
}

TEST(BadInput, AMistypedCommandGetsASuggestion) {
  const CommandResult r = ddafit("simulat", "mistyped");
  expect_refused(r, "did you mean 'simulate'");
}

// Starts `ddafit ARGS...`, sends `signal` after `delay`, and returns its exit status.
int run_and_signal(const std::vector<std::string>& args, int signal, std::chrono::milliseconds delay) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(DDAFIT_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(DDAFIT_BINARY, argv.data());
    _exit(127);
  }
  std::this_thread::sleep_for(delay);
  kill(pid, signal);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

TEST(BadInput, SigintAndSigtermKeepTheRunSoFar) {
  // A 300 s incline run takes far longer than the 1.5 s before the signal; the run must
  // stop with its history and an `interrupted` summary, exit 130 (SIGINT) or 143 (SIGTERM).
  for (const auto& [signal, code] : {std::pair{SIGINT, 130}, std::pair{SIGTERM, 143}}) {
    SCOPED_TRACE(signal);
    const fs::path out = fs::path(DDAFIT_TEST_TMP) / ("signal_" + std::to_string(signal));
    fs::remove_all(out);
    const int status = run_and_signal({"simulate", kIncline, "--set", "time.duration=300", "--out", out.string(), "--quiet"},
                                      signal, std::chrono::milliseconds(1500));
    EXPECT_EQ(status, code);
    const auto summary = nlohmann::json::parse(slurp(out / "summary.json"));
    EXPECT_EQ(summary["status"], "interrupted");
    const double reached = summary["run"]["simulated_time"].get<double>();
    EXPECT_GT(reached, 0.0);
    EXPECT_LT(reached, 300.0);
    // The history holds t = 0 and the rows up to the stop, not just a header.
    int rows = 0;
    std::ifstream csv(out / "history.csv");
    for (std::string line; std::getline(csv, line);) ++rows;
    EXPECT_GT(rows, 2);
  }
}

}  // namespace
