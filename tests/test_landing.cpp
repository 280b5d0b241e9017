// A block that drops a little onto a surface while sliding: the landing's normal impulse
// J_n brings a Coulomb friction impulse mu J_n with it (an inelastic impact that does not
// stop the slip), so the block's slide after landing is set by what it had when it landed.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

// (solver, gap m, speed m/s, friction angle deg)
using Landing = std::tuple<Integrator, double, double, double>;
class LevelLanding : public ::testing::TestWithParam<Landing> {};

TEST_P(LevelLanding, ABlockDroppedWhileSlidingStopsWhereCoulombSays) {
  // Flight t_f = sqrt(2 gap / g) at speed v0; landing at v_n = g t_f takes mu v_n off the
  // slip speed; then it decelerates at mu g: x = v0 t_f + (v0 - mu v_n)^2 / (2 mu g).
  const auto [solver, gap, v0, phi] = GetParam();
  Scene s = verification::incline_scene({});
  s.blocks.clear();
  s.interfaces[0].friction_angle = phi;
  s.interfaces[0].roughness_angle = 0.0;
  s.duration = 1.5;
  s.blocks.push_back(verification::block("base", {{-5, -2}, {40, -2}, {40, 0}, {-5, 0}}, true));
  BlockInput b = verification::block("slider", {{0, gap}, {2, gap}, {2, 1 + gap}, {0, 1 + gap}}, false);
  b.velocity = Vec2(v0, 0.0);
  s.blocks.push_back(b);
  s.measure = {{"c", {1.0, 0.5 + gap}}};
  s.options.integrator = solver;
  const SimulationResult r = simulate(s);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
  const double g = 9.81, mu = std::tan(phi * M_PI / 180.0);
  const double tf = std::sqrt(2.0 * gap / g), v = v0 - mu * g * tf;
  const double expected = v0 * tf + v * v / (2.0 * mu * g);
  // 0.1 mm: measured <= 0.02 mm over these cases; the step's own error is O(v dt^2).
  EXPECT_NEAR(r.history.back().displacement.x(), expected, 1e-4) << "gap " << gap << " v0 " << v0 << " phi " << phi;
}

INSTANTIATE_TEST_SUITE_P(Sweep, LevelLanding,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Values(1e-4, 1e-3, 1e-2), ::testing::Values(1.0, 2.0),
                                            ::testing::Values(20.0, 35.0)));

// Known defect (docs/speed-accuracy.md, "A block that lands on a slope"): on the 2:1
// incline (phi 25 deg, no degradation) a slider started 1e-4 m above the slope slides
// 8.3 mm (substep) and 14.7 mm (implicit) further in 2 s than one started on it, where
// the landing's friction impulse should cancel what the flight gained (< 0.1 mm apart).
TEST(SlopeLanding, DISABLED_ASliderDroppedOntoTheSlopeSlidesAsIfPlacedOnIt) {
  for (const Integrator solver : {Integrator::Implicit, Integrator::Substep}) {
    verification::InclineSetup setup;
    Scene placed = verification::incline_scene(setup);
    placed.options.integrator = solver;
    Scene dropped = placed;
    const Vec2 up = Vec2(1.0, 2.0).normalized();
    for (Vec2& p : dropped.blocks[1].polygon) p += 1e-4 * up;
    dropped.measure[0].at += 1e-4 * up;
    const double a = simulate(placed).summary.points[0].max_total_displacement;
    const double b = simulate(dropped).summary.points[0].max_total_displacement;
    EXPECT_NEAR(a, b, 1e-4) << to_string(solver);
  }
}

}  // namespace
}  // namespace ddafit
