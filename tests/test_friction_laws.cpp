// Every friction law (forward/contact/laws/) on the commonest scene it meets: a block
// sliding down a slope of flush fixed blocks, across their joints. The block's motion
// along the slope is d'' = g (sin alpha - cos alpha mu(d, d')), integrated here by RK4 with
// its own statement of each law (not the product's), and the simulated displacement must
// follow it within 1 % (the tolerance) at every output where the block has moved
// 1 cm, on both solvers, with the energy audit and overlap checks of the contact tests.
//
// Asserted as a class: slopes from 22 to 40 deg, peak angles with 4-12 deg of roughness,
// sliders 0.5-3 m long, joints every 0.3-2.5 m, d_c from 1 % to 25 % of the slider, v_w from
// 0.05 to 1 m/s, from rest, and at 2 m/s on slopes gentler than the peak angle (it slides
// on) and than the residual angle (it slows down and sticks: a rate law regains its peak).
#include <functional>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

constexpr double kGravity = 9.81;

// mu(d, v) of each law, written from its equation (docs/scene-format.md, "Friction laws").
double law_coefficient(const Crossing& c, double d, double v) {
  const double mu_p = std::tan(c.friction * kDegree), mu_r = std::tan((c.friction - c.roughness) * kDegree);
  const double d_c = c.dc_ratio * c.length;
  switch (c.law) {
    case FrictionLaw::Bilinear: return std::tan((c.friction - c.roughness * std::min(d / d_c, 1.0)) * kDegree);
    case FrictionLaw::Exponential: return mu_r + (mu_p - mu_r) * std::exp(-d / d_c);
    case FrictionLaw::VelocityWeakening: return mu_r + (mu_p - mu_r) / (1.0 + std::abs(v) / c.weakening_velocity);
    case FrictionLaw::ThermalPressurization: break;  // its own tests: test_thermal_pressurization.cpp
  }
  return NAN;
}

// Distance down the slope at `times` (RK4, slope_scene.hpp; the law's kink at d_c costs
// the bilinear case O(h^2) locally: < 1e-9 m here).
std::vector<double> rk4_distance(const Crossing& c, const std::vector<double>& times) {
  const double sa = std::sin(c.slope * kDegree), ca = std::cos(c.slope * kDegree);
  return rk4_slide([&](double d, double v) { return kGravity * (sa - ca * law_coefficient(c, d, v)); }, c.speed, times);
}

void expect_law_followed(const Crossing& c, Integrator integrator) {
  const Scene scene = crossing_scene(c, integrator);
  RunAudit audit;
  const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
  const std::string label = describe(c, integrator) + ", d_c/L " + std::to_string(c.dc_ratio) + ", v_w " +
                            std::to_string(c.weakening_velocity);
  expect_contact_physics(r, audit, integrator, label);
  const SlideError e = slide_error(r, Slope(c.slope), [&](const std::vector<double>& t) { return rk4_distance(c, t); });
  EXPECT_GT(e.final_distance, 0.1) << label << ": the case must slide";
  EXPECT_LT(e.worst, kDisplacementTolerance) << label << ": worst at t = " << e.when << " s";
  const double worst = e.worst;
  std::cout << "[measured] " << label << ": displacement error " << worst << "\n";
}

// The sweep: each law meets every geometry, and each geometry a different d_c and v_w.
std::vector<Crossing> law_sweep(FrictionLaw law) {
  struct Geometry {
    double slope, friction, roughness, length, height, spacing, speed, dc_ratio, weakening_velocity;
  };
  const Geometry geometries[] = {
      {28, 25, 5, 1.2, 0.6, 1.0, 0.0, 0.01, 0.1},   // the seed's kind of loss, joints every metre
      {40, 32, 12, 3.0, 0.8, 2.5, 0.0, 0.25, 1.0},  // steep, long slider, d_c across joints
      {22, 21, 8, 0.5, 0.5, 0.3, 0.0, 0.05, 0.05},  // just past peak: slow start, many joints
      {20, 25, 10, 2.0, 0.25, 1.0, 2.0, 0.1, 0.3},  // gentler than phi_p, kept sliding at 2 m/s
      {15, 25, 5, 1.2, 0.6, 0.5, 2.0, 0.01, 0.1},   // gentler than phi_r: slows down and sticks
  };
  std::vector<Crossing> cases;
  for (const Geometry& g : geometries) {
    Crossing c;
    c.slope = g.slope;
    c.friction = g.friction;
    c.roughness = g.roughness;
    c.length = g.length;
    c.height = g.height;
    c.spacing = g.spacing;
    c.speed = g.speed;
    c.dc_ratio = g.dc_ratio;
    c.weakening_velocity = g.weakening_velocity;
    c.front_gap = 0.02;
    c.law = law;
    cases.push_back(c);
  }
  return cases;
}

using LawParam = std::tuple<Integrator, FrictionLaw, int>;
class FrictionLaws : public ::testing::TestWithParam<LawParam> {};

TEST_P(FrictionLaws, SliderFollowsItsEquationOfMotionAcrossJoints) {
  const auto [integrator, law, index] = GetParam();
  expect_law_followed(law_sweep(law)[static_cast<size_t>(index)], integrator);
}

INSTANTIATE_TEST_SUITE_P(Sweep, FrictionLaws,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Values(FrictionLaw::Bilinear, FrictionLaw::Exponential,
                                                              FrictionLaw::VelocityWeakening),
                                            ::testing::Range(0, 5)),
                         [](const ::testing::TestParamInfo<LawParam>& info) {
                           return name_of(std::get<0>(info.param)) + "_" + to_string(std::get<1>(info.param)) + "_" +
                                  std::to_string(std::get<2>(info.param));
                         });

}  // namespace
}  // namespace ddafit
