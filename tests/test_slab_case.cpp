// A user's first scene of their own slide (cases/slab/slab.yaml): a 20 m slab on a 35 deg
// slope above a flat valley floor, two CSV profiles, two joint sets, 13-48 blocks on one
// fixed block of bedrock. On main before the shared contact stage the default solver
// stopped with "contacts are creating energy" in 5 of 8 such runs, and where both solvers
// completed their runouts differed by 14-32 %. At every block size and step here the run
// must complete on the default (auto: the implicit solver below 100 blocks) and on the
// substep solver, with overlaps within the 1 % of the smaller block; and the two
// solvers must agree on the slab top's runout.
//
// Agreement is judged on the mean over the six settings, within the 10 %: a single
// run is one sample of a chaotic slide (blocks tumbling onto the valley floor). Measured:
// the implicit solver's runouts scatter 86-98 m over these settings (and 84-96 m with other
// open-close limits), the substep solver's 96-99 m; the means differ by 4 %, the implicit
// solver's elastic blocks and its time scheme dissipating more at impacts. Each run must
// also lie within 20 % of the other solver's mean: one run's scatter and the bias with
// room, and still far from the 14-32 % and the failures seen before. The scatter of one
// setting, 15 m blocks at 10 ms, eight realisations (--ensemble 8): implicit 79.0-94.2 m
// (87.4 +- 5.4) with impacts resolved as impulses (revision 2026-11-26.3), 81.2-94.9 m
// (89.1 +- 5.3) before; substep 92.9-93.4 m (docs/speed-accuracy.md).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <numeric>
#include <vector>

#include "forward/io/scene_reader.hpp"
#include "forward/run_record.hpp"
#include "forward/simulation.hpp"

namespace ddafit {
namespace {

constexpr double kMaxOverlapRatio = kOverlapBoundRatio;  // 1 % (run_record.hpp)
constexpr double kRunoutAgreement = 0.10;
const std::string kSlab = std::string(DDAFIT_CASES_DIR) + "/slab/slab.yaml";

TEST(SlabCase, CompletesOnBothSolversAndTheirRunoutsAgree) {
  constexpr double kRunAgreement = 0.20;
  std::vector<double> runouts[2];  // auto (implicit), substep
  for (const double size : {8.0, 10.0, 15.0})
    for (const double step : {0.005, 0.01})
      for (int k = 0; k < 2; ++k) {
        const std::string solver = k == 0 ? "auto" : "substep";
        const Scene scene = io::read_scene(
            kSlab, {{"mesh.block_size", std::to_string(size)}, {"time.step", std::to_string(step)},
                    {"time.integrator", solver}});
        const SimulationResult r = simulate(scene);
        const std::string label = "slab at " + std::to_string(size) + " m, " + std::to_string(step) + " s, " + solver;
        ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
        if (k == 0) {
          EXPECT_EQ(r.summary.solver.integrator, Integrator::Implicit) << label;
        }
        EXPECT_LE(r.summary.solver.worst_penetration_ratio, kMaxOverlapRatio)
            << label << ": overlap between " << r.summary.solver.worst_penetration_at;
        ASSERT_EQ(r.summary.points.size(), 2u);
        runouts[k].push_back(r.summary.points[0].max_lateral_displacement);
        // The slab reaches the valley floor: its top runs out tens of metres.
        EXPECT_GT(runouts[k].back(), 50.0) << label;
        std::cout << "[measured] " << label << ": top's runout " << runouts[k].back() << " m, worst overlap "
                  << r.summary.solver.worst_penetration_ratio << ", wall " << r.summary.profile.total << " s\n";
      }
  const auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); };
  const double implicit = mean(runouts[0]), substep = mean(runouts[1]);
  EXPECT_LE(std::abs(implicit - substep), kRunoutAgreement * 0.5 * (implicit + substep))
      << "mean runout: implicit " << implicit << " m, substep " << substep << " m";
  for (size_t i = 0; i < runouts[0].size(); ++i) {
    EXPECT_LE(std::abs(runouts[0][i] - substep), kRunAgreement * substep) << "implicit run " << i;
    EXPECT_LE(std::abs(runouts[1][i] - implicit), kRunAgreement * implicit) << "substep run " << i;
  }
  std::cout << "[measured] mean runout of the slab's top: implicit " << implicit << " m, substep " << substep << " m\n";
}

}  // namespace
}  // namespace ddafit
