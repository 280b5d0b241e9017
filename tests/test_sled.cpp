// Fidelity 0 (forward/sled/sled.hpp): on one plane the sled is seed Eq. 4 (constant friction)
// and Eq. 5 (the bilinear degradation), to 1e-6 of the distance; on the Vajont stand-in its
// static friction angle is the coherent-mass limit equilibrium of shared/data/vajont/README.md,
// 22.0 deg (+-0.5, the tolerance).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "forward/simulation.hpp"
#include "tests/cli_run.hpp"
#include "verify/analytic.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

TEST(Sled, OnOnePlaneItIsSeedEquations4And5) {
  struct Case {
    double friction, roughness, slope_ratio;
  };
  for (const Case& c : {Case{25.0, 0.0, 0.5}, Case{25.0, 5.0, 0.5}, Case{20.0, 8.0, 0.7}, Case{30.0, 10.0, 0.6},
                        Case{30.0, 0.0, 0.5}}) {
    verification::InclineSetup setup;
    setup.friction_angle = c.friction;
    setup.roughness_angle = c.roughness;
    setup.slope_ratio = c.slope_ratio;
    Scene scene = verification::incline_scene(setup);
    scene.options.integrator = Integrator::Sled;
    const SimulationResult r = simulate(scene);
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
    // The same plane mirrored (dipping towards -x): the sled slides the other way, the law
    // reading the slip, not the signed distance.
    Scene mirrored = scene;
    for (BlockInput& b : mirrored.blocks)
      for (Vec2& p : b.polygon) p.x() = -p.x();
    for (MeasurePoint& m : mirrored.measure) m.at.x() = -m.at.x();
    const SimulationResult back = simulate(mirrored);
    ASSERT_EQ(back.summary.status, RunStatus::Completed) << back.summary.message;
    ASSERT_EQ(back.sled.series.size(), r.sled.series.size());
    for (size_t k = 0; k < r.sled.series.size(); ++k)
      ASSERT_NEAR(back.sled.series[k].distance, -r.sled.series[k].distance, 1e-9 + 1e-9 * std::abs(r.sled.series[k].distance))
          << "mirrored, t = " << r.sled.series[k].time;
    verification::InclineAnalytic exact;
    exact.slope_angle = std::atan(c.slope_ratio) * 180.0 / M_PI;
    exact.friction_angle = c.friction;
    exact.roughness_angle = c.roughness;
    exact.critical_distance = 0.01 * verification::kInclineBlockLength;
    std::vector<double> times, distance, speed;
    for (const SledPoint& p : r.sled.series) times.push_back(p.time);
    exact.solve(times, distance, speed);
    double worst = 0.0, scale = 0.0;
    for (size_t k = 0; k < times.size(); ++k) {
      worst = std::max(worst, std::abs(r.sled.series[k].distance - distance[k]));
      scale = std::max(scale, std::abs(distance[k]));
    }
    const std::string label = "phi " + std::to_string(c.friction) + ", i " + std::to_string(c.roughness) +
                              ", tan(alpha) " + std::to_string(c.slope_ratio);
    if (scale == 0.0) {
      EXPECT_EQ(worst, 0.0) << label << ": held by friction, the sled must not move";
    } else {
      EXPECT_LT(worst, 1e-6 * scale) << label;
    }
    // The measure point moves down the plane by the sled's distance (the recorder's history).
    const Vec2 along(1.0 / std::sqrt(1.0 + c.slope_ratio * c.slope_ratio),
                     -c.slope_ratio / std::sqrt(1.0 + c.slope_ratio * c.slope_ratio));
    EXPECT_NEAR(r.history.back().displacement.dot(along), r.sled.series.back().distance, 1e-9 + 1e-9 * scale) << label;
    std::cout << "[measured] sled, " << label << ": worst distance error " << worst << " m of " << scale << " m\n";
  }
}

TEST(Sled, TheVajontStandInIsJustStableAtTheLimitEquilibriumAngle) {
  const std::string out = std::string(DDAFIT_TEST_TMP) + "/sled_vajont";
  const ddafit_test::CommandResult r = ddafit_test::ddafit(
      "sled " + std::string(DDAFIT_CASES_DIR) + "/vajont/vajont.yaml --set mesh.block_size=34.3 --out " + out, "sled_vajont_run");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ddafit_test::slurp(out + "/sled.json"));
  const double angle = j.at("static_friction_angle").get<double>();
  EXPECT_NEAR(angle, 22.0, 0.5) << "shared/data/vajont/README.md: coherent-mass limit equilibrium 22.0 deg";
  std::cout << "[measured] Vajont stand-in (section I blocks): sled static friction angle " << angle << " deg\n";
}

}  // namespace
}  // namespace ddafit
