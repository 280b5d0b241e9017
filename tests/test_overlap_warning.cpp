// The warning a completed run gives when its worst overlap is over the 1 % of the smaller block
// that ddafit's runs are checked to (forward/run_record.hpp, overlap_warning). The rule alone, on
// solver reports as both solvers fill them; a whole run that trips it is in test_vajont.cpp
// (section I with its position correction off).
#include <gtest/gtest.h>

#include <cmath>

#include "forward/run_record.hpp"

namespace ddafit {
namespace {

SolverReport report_at(Integrator integrator, double ratio) {
  SolverReport r;
  r.integrator = integrator;
  r.worst_penetration = 0.01;
  r.worst_penetration_ratio = ratio;
  r.worst_penetration_time = 2.5;
  r.worst_penetration_at = "blocks 'a' and 'b'";
  return r;
}

// At the bound a run passes (the tests and the Vajont sections hold <= 1 %); the next double up
// is over it, on either solver.
TEST(OverlapWarning, StartsJustPastTheBound) {
  Scene scene;
  scene.max_step = 0.02;
  for (const Integrator integrator : {Integrator::Substep, Integrator::Implicit}) {
    EXPECT_EQ(overlap_warning(scene, report_at(integrator, kOverlapBoundRatio)), "");
    EXPECT_EQ(overlap_warning(scene, report_at(integrator, 0.0)), "");
    const std::string w = overlap_warning(scene, report_at(integrator, std::nextafter(kOverlapBoundRatio, 1.0)));
    EXPECT_NE(w.find("blocks 'a' and 'b'"), std::string::npos) << w;
    EXPECT_NE(w.find("t = 2.5 s"), std::string::npos) << w;
  }
}

// Each solver is told what holds its blocks apart: the substep solver its step and substeps (and
// the deep-overlap ratio when the scene set one), the implicit solver its penetration limit.
TEST(OverlapWarning, NamesTheSettingsOfTheSolverThatRan) {
  Scene scene;
  scene.max_step = 0.02;
  scene.options.substeps = 4;
  const std::string substep = overlap_warning(scene, report_at(Integrator::Substep, 0.0132));
  EXPECT_NE(substep.find("1.32 % of the smaller block"), std::string::npos) << substep;
  EXPECT_NE(substep.find("time.step (now 0.02 s)"), std::string::npos) << substep;
  EXPECT_NE(substep.find("time.substeps (now 4)"), std::string::npos) << substep;
  EXPECT_EQ(substep.find("deep_overlap_ratio"), std::string::npos) << substep;  // automatic: not the user's
  scene.options.deep_overlap_ratio = 0.02;
  EXPECT_NE(overlap_warning(scene, report_at(Integrator::Substep, 0.0132)).find("deep_overlap_ratio (now 0.02)"),
            std::string::npos);
  const std::string implicit = overlap_warning(scene, report_at(Integrator::Implicit, 0.0132));
  EXPECT_NE(implicit.find("control.max_penetration_ratio"), std::string::npos) << implicit;
  EXPECT_EQ(implicit.find("substeps"), std::string::npos) << implicit;
}

}  // namespace
}  // namespace ddafit
