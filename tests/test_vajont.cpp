// The Vajont case in CI: it loads, and a coarse section slides the right way. The long
// runs (sections I-X, 40 s) belong in docs/vajont.md, not in the test suite.
#include <gtest/gtest.h>

#include <algorithm>

#include "forward/analysis/stable_friction.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/run_record.hpp"
#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

const std::string kScene = std::string(DDAFIT_CASES_DIR) + "/vajont/vajont.yaml";

// A run's warning about its worst overlap (run_record.hpp, overlap_warning).
bool is_overlap_warning(const std::string& w) { return w.find("the worst overlap") != std::string::npos; }

TEST(Vajont, CoarseSectionSlidesDownslopeOnAFixedBase) {
  // Section I (34.3 m blocks), 1 s of the reference state. With 12 deg basal friction on
  // a base dipping 34 deg at the top, the mass must start moving down and towards the
  // valley (+x, -y) at every measurement point within the first second.
  const Scene scene = io::read_scene(kScene, {{"mesh.block_size", "34.3"}, {"time.duration", "1.0"}});
  std::vector<Vec2> bedrock_before;
  for (const BlockInput& b : scene.blocks)
    if (b.fixed) bedrock_before.insert(bedrock_before.end(), b.polygon.begin(), b.polygon.end());
  std::vector<Vec2> bedrock_after;
  SimulationHooks hooks;
  hooks.on_output = [&](double, const BlockSystem& s) {
    bedrock_after.clear();
    for (const Block& b : s.blocks)
      if (b.fixed)
        bedrock_after.insert(bedrock_after.end(), s.vertices.begin() + b.first_vertex,
                             s.vertices.begin() + b.first_vertex + b.vertex_count);
  };
  const SimulationResult r = simulate(scene, hooks);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  for (size_t k = 0; k < scene.measure.size(); ++k) {
    const HistoryRow& last = r.history[r.history.size() - scene.measure.size() + k];
    const std::string& name = scene.measure[k].name;
    EXPECT_GT(last.displacement.x(), 0.05) << "point " << name;  // towards the valley
    // Down where the base is steep (points 1-4); point 5 and the vertical profile stand
    // on or above the 1-13 deg seat and may be pushed up over it.
    if (name == "1" || name == "2" || name == "3" || name == "4") {
      EXPECT_LT(last.displacement.y(), 0.0) << name;
    }
  }
  // The bedrock is fixed: not a vertex may move (exact, no tolerance needed). Compared
  // as sets, since the engine orders every polygon counter-clockwise.
  const auto by_xy = [](const Vec2& a, const Vec2& b) { return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y(); };
  std::sort(bedrock_before.begin(), bedrock_before.end(), by_xy);
  std::sort(bedrock_after.begin(), bedrock_after.end(), by_xy);
  EXPECT_EQ(bedrock_after, bedrock_before);
}

// A slope that must stand (issue: the substep solver's throwaway prototype crept metres
// in 2 s here): section I with 40 deg on the base and on every joint, 5 s, the solver the
// scene picks (substep, 183 blocks). 40 deg is far above the ~20 deg at which section I
// starts to slide (docs/vajont.md, stable state), so nothing may move beyond elastic
// settling: 5 cm is the bound (the implicit solver, whose blocks strain, settles
// 2.7 cm; the substep solver's rigid blocks measured under 0.1 mm).
TEST(Vajont, SlopeAtFortyDegreesStands) {
  const Scene scene = io::read_scene(kScene, {{"mesh.block_size", "34.3"},
                                              {"interfaces.clay.friction_angle", "40"},
                                              {"time.duration", "5.0"}});
  const SimulationResult r = simulate(scene);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  EXPECT_EQ(r.summary.solver.integrator, Integrator::Substep);
  for (const PointSummary& p : r.summary.points) EXPECT_LT(p.max_total_displacement, 0.05) << "point " << p.name;
}

// Section I, degraded state, the whole 45 s with the substep solver: the run completes
// with the energy audit on, the slide runs out (point 1 lateral between 250 and 450 m:
// the implicit solver gives 338 m, the substep solver 293-347 m over revisions and step
// settings, docs/speed-accuracy.md, docs/vajont.md), and no contact point overlaps deeper than
// the 1 % of the smaller block the runs are checked to (run_record.hpp, kOverlapBoundRatio;
// measured 0.40 % at model revision 2026-12-07.5, docs/vajont.md; 1.47 % at revision .1, when
// this test allowed 2.5 %), so the run gives no overlap warning.
TEST(Vajont, SectionOneDegradedCompletesWithShallowOverlaps) {
  const Scene scene = io::read_scene(std::string(DDAFIT_CASES_DIR) + "/vajont/degraded.yaml",
                                     {{"mesh.block_size", "34.3"}});
  const SimulationResult r = simulate(scene);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  EXPECT_EQ(r.summary.solver.integrator, Integrator::Substep);
  EXPECT_LE(r.summary.solver.worst_penetration_ratio, kOverlapBoundRatio) << r.summary.solver.worst_penetration_at;
  EXPECT_TRUE(std::none_of(r.summary.warnings.begin(), r.summary.warnings.end(), is_overlap_warning));
  const PointSummary& top = r.summary.points.front();
  EXPECT_GT(top.max_lateral_displacement, 250.0);
  EXPECT_LT(top.max_lateral_displacement, 450.0);
}

// The same section with its position correction of deep overlaps switched off
// (control.deep_overlap_ratio 0.1) at 0.1 s steps of two substeps, 10 s: the blocks sink
// into each other (5.8 % of the smaller block at revision 2026-12-07.5; 0.33 % with the correction
// still off at the scene's 20 ms x 4) but the run completes, and says so: the warning names the
// two blocks and the three settings that would hold them apart (run_record.hpp).
TEST(Vajont, ARunCompletedDeeperThanTheBoundSaysSo) {
  const Scene scene = io::read_scene(std::string(DDAFIT_CASES_DIR) + "/vajont/degraded.yaml",
                                     {{"mesh.block_size", "34.3"},
                                      {"control.deep_overlap_ratio", "0.1"},
                                      {"time.step", "0.1"},
                                      {"time.substeps", "2"},
                                      {"time.duration", "10"}});
  const SimulationResult r = simulate(scene);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  ASSERT_GT(r.summary.solver.worst_penetration_ratio, kOverlapBoundRatio);
  const auto warned = std::find_if(r.summary.warnings.begin(), r.summary.warnings.end(), is_overlap_warning);
  ASSERT_NE(warned, r.summary.warnings.end());
  EXPECT_NE(warned->find(r.summary.solver.worst_penetration_at), std::string::npos) << *warned;
  for (const char* setting : {"time.step (now 0.1 s)", "time.substeps (now 2)", "control.deep_overlap_ratio (now 0.1)"})
    EXPECT_NE(warned->find(setting), std::string::npos) << *warned;
}

TEST(Vajont, DegradedSceneInheritsAndDegrades) {
  // degraded.yaml is vajont.yaml with 25 % degradation: residual basal angle 9 deg,
  // mu = tan 9 = 0.158 (seed §3.4c).
  const Scene s = io::read_scene(std::string(DDAFIT_CASES_DIR) + "/vajont/degraded.yaml",
                                 {{"mesh.block_size", "34.3"}});
  ASSERT_EQ(s.interfaces.size(), 2u);
  EXPECT_DOUBLE_EQ(s.interfaces[0].friction_angle - s.interfaces[0].roughness_angle, 9.0);
  EXPECT_DOUBLE_EQ(s.interfaces[1].friction_angle - s.interfaces[1].roughness_angle, 30.0);
}

}  // namespace
}  // namespace ddafit
