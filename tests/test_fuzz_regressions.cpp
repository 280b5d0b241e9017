// The fuzz targets (fuzz/targets.hpp) over their checked-in seed corpora and over every
// input that ever broke ddafit (fuzz/regressions/TARGET): no time-based fuzzing in CI, but
// each of those inputs must keep reading or being refused with one printable line. A
// target that finds a problem aborts, which fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/targets.hpp"

namespace {

namespace fs = std::filesystem;
using Target = int (*)(const std::uint8_t*, std::size_t);

// Runs `target` on every file of fuzz/corpus/NAME and fuzz/regressions/NAME; returns how many.
int run_inputs(const std::string& name, Target target) {
  int inputs = 0;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(DDAFIT_FUZZ_DIR) / kind / name;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      SCOPED_TRACE(file.string());
      std::ifstream in(file, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      EXPECT_EQ(target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), 0);
      ++inputs;
    }
  }
  return inputs;
}

// At least one seed and one regression per target: an empty folder would pass silently.
TEST(FuzzRegressions, SceneReader) { EXPECT_GE(run_inputs("scene_reader", ddafit::fuzz::scene_reader), 2); }
TEST(FuzzRegressions, RegionMesh) { EXPECT_GE(run_inputs("region_mesh", ddafit::fuzz::region_mesh), 2); }
TEST(FuzzRegressions, Study) { EXPECT_GE(run_inputs("study", ddafit::fuzz::study), 2); }
TEST(FuzzRegressions, Ddaml) { EXPECT_GE(run_inputs("ddaml", ddafit::fuzz::ddaml), 2); }
TEST(FuzzRegressions, SetParser) { EXPECT_GE(run_inputs("set_parser", ddafit::fuzz::set_parser), 2); }

}  // namespace
