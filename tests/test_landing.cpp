// A block that drops a little onto a surface while sliding: the landing's normal impulse
// J_n brings a Coulomb friction impulse mu J_n with it (an inelastic impact that does not
// stop the slip), so the block's slide after landing is set by what it had when it landed.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

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

// A block dropped a small gap onto a plane inclined at alpha, friction phi: it flies for
// t_f = sqrt(2 gap / (g cos alpha)) and lands with v_n = g cos(alpha) t_f; the landing's
// friction impulse mu m v_n takes g sin(alpha) t_f - mu v_n off its slip (perfectly
// inelastic, Coulomb), leaving exactly what a block placed on the plane has at t_f,
// max(0, a t_f) with a = g (sin alpha - mu cos alpha). Then it slides on at a (or stays).
// Blocks that would topple (tan alpha >= w/h) or lift their rear corner at the landing
// (mu h >= w) are left out: their answer is not this formula.
struct SlopeDrop {
  double alpha, phi, gap, width, height;
};

Scene slope_drop_scene(const SlopeDrop& d, Integrator solver) {
  Scene s = verification::incline_scene({});
  s.blocks.clear();
  s.interfaces[0].friction_angle = d.phi;
  s.interfaces[0].roughness_angle = 0.0;
  s.duration = 1.0;
  const double a = d.alpha * M_PI / 180.0;
  const Vec2 along(std::cos(a), -std::sin(a)), up(std::sin(a), std::cos(a));
  s.blocks.push_back(verification::block("plane", {Vec2(0, 0), 40.0 * along, 40.0 * along - 3.0 * up, -3.0 * up}, true));
  const Vec2 o = 3.0 * along + d.gap * up;
  s.blocks.push_back(verification::block(
      "slider", {o, o + d.width * along, o + d.width * along + d.height * up, o + d.height * up}, false));
  s.measure = {{"c", o + 0.5 * d.width * along + 0.5 * d.height * up}};
  s.options.integrator = solver;
  return s;
}

// Slide along the plane at t = 1 s by the formula above.
double slope_drop_slide(const SlopeDrop& d) {
  const double g = 9.81, a = d.alpha * M_PI / 180.0, mu = std::tan(d.phi * M_PI / 180.0);
  const double tf = std::sqrt(2.0 * d.gap / (g * std::cos(a))), acc = g * (std::sin(a) - mu * std::cos(a));
  const double rest = 1.0 - tf, flight = 0.5 * g * std::sin(a) * tf * tf;
  return acc > 0.0 ? flight + acc * tf * rest + 0.5 * acc * rest * rest : flight;
}

std::vector<SlopeDrop> slope_drops() {
  std::vector<SlopeDrop> out;
  for (const double alpha : {15.0, 26.565, 40.0})
    for (const double dphi : {-8.0, -1.5, -0.3, 2.0})  // from sliding freely to just held
      for (const double gap : {1e-5, 1e-4, 1e-3})
        for (const auto& [w, h] : {std::pair{2.0, 1.0}, std::pair{2.23, 2.05}, std::pair{1.0, 1.8}}) {
          const double phi = alpha + dphi;
          if (std::tan(alpha * M_PI / 180.0) >= w / h || std::tan(phi * M_PI / 180.0) * h >= w) continue;
          out.push_back({alpha, phi, gap, w, h});
        }
  return out;
}

// On 2026-11-26 (model revision .1, control.contact_passes 16): worst error 3.3e-6 m over
// the 96 drops; with one pass per manifold (revision 2026-11-25.3) 51 of them erred by
// more than 5e-5 m (up to 1.7e-2 m). 5e-5 m keeps a margin of 15 over the measured error.
TEST(SlopeLanding, ABlockDroppedOntoASlopeSlidesOnAsCoulombSays) {
  const std::vector<SlopeDrop> drops = slope_drops();
  ASSERT_GE(drops.size(), 90u);
  for (const SlopeDrop& d : drops) {
    const SimulationResult r = simulate(slope_drop_scene(d, Integrator::Substep));
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
    const double a = d.alpha * M_PI / 180.0;
    const double slide = Vec2(std::cos(a), -std::sin(a)).dot(r.history.back().displacement);
    EXPECT_NEAR(slide, slope_drop_slide(d), 5e-5)
        << "alpha " << d.alpha << " phi " << d.phi << " gap " << d.gap << " block " << d.width << " x " << d.height;
  }
}

// The implicit solver resolves a landing as an inelastic rigid impulse with its Coulomb
// friction before the step (forward/step/resolve_impacts.hpp). Without that stage its
// penalty springs returned part of the landing's normal velocity (the 2.23 x 2.05 m block
// dropped 1e-4 m onto the 2:1 slope rebounded at 1.7 cm/s of its 4.2 cm/s) and 65 of these
// 96 drops missed the formula by more than 5e-5 m in 1 s, up to 5.2e-2 m. With it
// (2026-11-26, revision .3) the worst is 1.6e-3 m, and what is left is not the landing: the
// same blocks placed on the slope (gap 0) err by up to 5.1e-4 m with the friction angle
// 1.5 deg below the slope's and 9.7e-4 m at 0.3 deg (the start of sliding through the
// locked shear spring, growing as the step shrinks: 8.7e-4 m at 2 ms, 1.3e-3 m at 0.25 ms).
// Far from the friction angle (8 deg below it, or held) all drops land within 1.2e-5 m and
// are held to 5e-5 m; the near ones to 2.5e-3 m, a margin of 1.5 over the worst.
TEST(SlopeLanding, TheImplicitSolverLandsABlockAsCoulombSays) {
  for (const SlopeDrop& d : slope_drops()) {
    const SimulationResult r = simulate(slope_drop_scene(d, Integrator::Implicit));
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
    const double a = d.alpha * M_PI / 180.0;
    const bool near = std::abs(d.phi - d.alpha) < 2.0 && d.phi < d.alpha;
    EXPECT_NEAR(Vec2(std::cos(a), -std::sin(a)).dot(r.history.back().displacement), slope_drop_slide(d),
                near ? 2.5e-3 : 5e-5)
        << "alpha " << d.alpha << " phi " << d.phi << " gap " << d.gap << " block " << d.width << " x " << d.height;
  }
}

}  // namespace
}  // namespace ddafit
