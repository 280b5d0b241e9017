// `ddafit import`: the XML input of the UC Berkeley DDA codes (DDAML, github doolin/ntdda)
// as a ddafit scene. Small files written for these tests (cases/ddaml: an incline, a stack,
// a brick wall) are imported, run, and compared with the analytic answer; every element
// ddafit cannot represent is refused with its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "forward/geometry.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/simulation.hpp"
#include "tests/cli_run.hpp"

namespace ddafit {
namespace {

using ddafit_test::slurp;
namespace fs = std::filesystem;

const std::string kDdaml = std::string(DDAFIT_CASES_DIR) + "/ddaml/";

Scene imported(const std::string& name, const std::string& units = "kN") {
  const fs::path out = fs::path(DDAFIT_TEST_TMP) / "ddaml" / (name + "_" + units + ".yaml");
  fs::create_directories(out.parent_path());
  const auto r = ddafit_test::ddafit("import " + kDdaml + name + ".geo --analysis " + kDdaml + name + ".ana --units " +
                                         units + " --out " + out.string(), "ddaml/" + name + "_" + units);
  EXPECT_EQ(r.code, 0) << r.err;
  return io::read_scene(out.string());
}

TEST(DdamlImport, TheInclineSlidesAsSeedEq4OnBothSolvers) {
  const Scene scene = imported("incline");
  ASSERT_EQ(scene.blocks.size(), 2u);
  EXPECT_DOUBLE_EQ(scene.materials[0].density, 2700.0);        // 2.7 t/m^3
  EXPECT_DOUBLE_EQ(scene.materials[0].young_modulus, 5.0e9);  // 5e6 kPa
  EXPECT_DOUBLE_EQ(scene.duration, 2.0);                       // 2000 steps of 1 ms
  EXPECT_DOUBLE_EQ(scene.output_interval, 0.01);               // every 10th step
  // Seed Eq. 4 on the 2:1 slope, phi 25 deg: s = g (sin a - cos a tan phi) t^2 / 2.
  const double a = std::atan(0.5);
  const double s = 0.5 * 9.81 * (std::sin(a) - std::cos(a) * std::tan(25.0 * M_PI / 180.0)) * 4.0;
  for (const Integrator solver : {Integrator::Implicit, Integrator::Substep}) {
    Scene run = scene;
    run.options.integrator = solver;
    const SimulationResult r = simulate(run);
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
    // 1 %: the bound; both solvers are within 0.1 % of it on ddafit's own incline.
    EXPECT_NEAR(r.summary.points[0].max_total_displacement, s, 0.01 * s) << to_string(solver);
  }
}

TEST(DdamlImport, SiUnitsReadTheSameScene) {
  // incline.ana in SI: unit mass in kg/m^3 and Young's modulus in Pa.
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / "ddaml_si";
  fs::create_directories(dir);
  std::string ana = slurp(kDdaml + "incline.ana");
  ana.replace(ana.find("<Unitmass> 2.7 "), 15, "<Unitmass> 2700 ");
  ana.replace(ana.find("<Youngsmod> 5000000 "), 20, "<Youngsmod> 5e9 ");
  std::ofstream(dir / "incline.ana") << ana;
  fs::copy_file(kDdaml + "incline.geo", dir / "incline.geo", fs::copy_options::overwrite_existing);
  const auto r = ddafit_test::ddafit("import " + (dir / "incline.geo").string() + " --analysis " +
                                         (dir / "incline.ana").string() + " --units SI --out " + (dir / "s.yaml").string(),
                                     "ddaml_si/cmd");
  ASSERT_EQ(r.code, 0) << r.err;
  const Scene si = io::read_scene((dir / "s.yaml").string()), kn = imported("incline");
  EXPECT_EQ(si.materials[0].density, kn.materials[0].density);
  EXPECT_EQ(si.materials[0].young_modulus, kn.materials[0].young_modulus);
}

TEST(DdamlImport, AStackAndABrickWallStandStill) {
  for (const std::string name : {"stack", "brick_wall"}) {
    const Scene scene = imported(name);
    // The cutter: the stack's base and three blocks; the wall's base and 3 + 4 + 3 bricks
    // covering 6 x 3 m, the overshooting joint ends dropped.
    double free_area = 0.0;
    int free = 0;
    for (const BlockInput& b : scene.blocks)
      if (!b.fixed) free_area += std::abs(signed_area(b.polygon)), ++free;
    EXPECT_EQ(free, name == "stack" ? 3 : 10);
    EXPECT_NEAR(free_area, name == "stack" ? 3.0 : 18.0, 1e-9);
    for (const Integrator solver : {Integrator::Implicit, Integrator::Substep}) {
      Scene run = scene;
      run.options.integrator = solver;
      const SimulationResult r = simulate(run);
      ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
      // At rest (friction 35 deg, no load but gravity): 1 mm allows the contacts' settling.
      for (const PointSummary& p : r.summary.points)
        EXPECT_LT(p.max_total_displacement, 1e-3) << name << " " << to_string(solver) << " point " << p.name;
    }
  }
}

struct Refusal {
  const char* what;
  const char* file;     // "geo" or "ana": which file gets the change
  const char* find;     // text replaced
  const char* replace;  // by this, which carries the line to be named
  const char* message;  // part of the one-line refusal
  const char* line_of;  // the text whose line the refusal names ("" = any)
};

TEST(DdamlImport, WhatDdafitCannotRepresentIsRefusedWithItsLine) {
  const Refusal cases[] = {
      {"load point", "geo", "   <Measuredpointlist>", "   <Loadpointlist>\n      <Point> 3.4 -0.5 </Point>\n   </Loadpointlist>\n   <Measuredpointlist>", "point loads are not modelled", "<Point> 3.4 -0.5"},
      {"bolt", "geo", "   <Measuredpointlist>", "   <Boltlist>\n      <Bolt type=\"1\"> 3 -0.5 3.5 -0.2 </Bolt>\n   </Boltlist>\n   <Measuredpointlist>", "rock bolts are not modelled", "<Bolt type"},
      {"pin", "geo", "      <Point> 10 -6 </Point>\n", "      <Point> 10 -6 </Point>\n      <Point> 3.4 -0.5 </Point>\n", "a pin", "<Point> 3.4 -0.5"},
      {"initial stress", "ana", "<Istress> 0 0 0 </Istress>", "<Istress> 0 -50 0 </Istress>", "initial stresses are not modelled", "<Istress> 0 -50"},
      {"static", "ana", "<Analysistype type=\"dynamic\"/>", "<Analysistype type=\"static\"/>", "static analysis", "type=\"static\""},
      {"joint without type", "geo", "<Joint type=\"1\"> 0 -2 0 0 </Joint>", "<Joint> 0 -2 0 0 </Joint>", "attribute 'type' is missing", "<Joint> 0 -2"},
      {"three numbers", "geo", "<Joint type=\"1\"> 0 -2 0 0 </Joint>", "<Joint type=\"1\"> 0 -2 0 </Joint>", "needs 4 numbers, has 3", "0 -2 0 </Joint>"},
      {"not XML", "geo", "<Jointlist>", "<Jointlist", "line", ""},
  };
  for (const Refusal& c : cases) {
    std::string tag = c.what;  // a folder name the shell command can carry
    std::replace(tag.begin(), tag.end(), ' ', '_');
    const fs::path dir = fs::path(DDAFIT_TEST_TMP) / "ddaml_refused" / tag;
    fs::create_directories(dir);
    std::string geo = slurp(kDdaml + "incline.geo"), ana = slurp(kDdaml + "incline.ana");
    std::string& text = std::string(c.file) == "geo" ? geo : ana;
    const size_t at = text.find(c.find);
    ASSERT_NE(at, std::string::npos) << c.what;
    text.replace(at, std::string(c.find).size(), c.replace);
    std::ofstream(dir / "in.geo") << geo;
    std::ofstream(dir / "in.ana") << ana;
    const auto r = ddafit_test::ddafit("import " + (dir / "in.geo").string() + " --analysis " + (dir / "in.ana").string() +
                                           " --units kN --out " + (dir / "s.yaml").string(),
                                       "ddaml_refused/" + tag + "/cmd");
    EXPECT_EQ(r.code, 2) << c.what << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.what << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.what << ": " << r.err;
    if (*c.line_of) {
      const std::string before = text.substr(0, text.find(c.line_of));
      const int line = 1 + static_cast<int>(std::count(before.begin(), before.end(), '\n'));
      EXPECT_NE(r.err.find(": line " + std::to_string(line) + ":"), std::string::npos) << c.what << ": " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "s.yaml")) << c.what;
  }
  // Found by review 2026-11-26: nesting deep enough would overflow the reader's stack.
  {
    const fs::path deep = fs::path(DDAFIT_TEST_TMP) / "ddaml_refused" / "deep.geo";
    std::string text;
    for (int k = 0; k < 100000; ++k) text += "<a>";
    std::ofstream(deep) << text;
    const auto r = ddafit_test::ddafit("import " + deep.string() + " --units SI --out " +
                                           (deep.parent_path() / "deep.yaml").string(), "ddaml_refused/deep");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.signal, 0);
    EXPECT_NE(r.err.find("nested deeper than 64"), std::string::npos) << r.err;
  }
  // Units are never guessed.
  const auto r = ddafit_test::ddafit("import " + kDdaml + "incline.geo --out " +
                                         (fs::path(DDAFIT_TEST_TMP) / "ddaml_refused" / "u.yaml").string(),
                                     "ddaml_refused/units");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--units"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace ddafit
