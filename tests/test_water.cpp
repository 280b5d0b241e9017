// Water in the slope (forward/water/hydrostatic.hpp): the hydrostatic pressure on every
// face below the water surface, faces in contact included, checked on both solvers against
// what Archimedes and Terzaghi give in closed form. Each within 1 % (the bound).
#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

constexpr double kG = 9.81, kWater = 1000.0;
constexpr double kTolerance = 0.01;

class Water : public ::testing::TestWithParam<Integrator> {};

// A block under water on an incline: buoyancy takes rho_w/rho of its weight off both the
// driving and the normal force (the pressure on its base, a face in contact, lowers the
// effective normal force), so it slides at a = g (1 - rho_w/rho)(sin a - cos a tan phi).
// Joints cross the slope, as in the friction-law tests; two slopes, two rock densities.
TEST_P(Water, ASubmergedBlockSlidesAtTheBuoyantAcceleration) {
  const Integrator integrator = GetParam();
  for (const auto& [slope, friction, density] : {std::tuple{28.0, 18.0, 2700.0}, std::tuple{40.0, 30.0, 2000.0}}) {
    Crossing c;
    c.slope = slope;
    c.friction = friction;
    Scene s = crossing_scene(c, integrator);
    s.materials[0].density = density;
    s.water.level = 5.0;  // the whole slope and slider lie below y = 2
    RunAudit audit;
    const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
    const std::string label = describe(c, integrator) + ", rho " + std::to_string(density);
    expect_contact_physics(r, audit, integrator, label);
    const double a = kG * (1.0 - kWater / density) *
                     (std::sin(slope * kDegree) - std::cos(slope * kDegree) * std::tan(friction * kDegree));
    const Slope along(slope);
    double worst = 0.0;
    for (const HistoryRow& row : r.history) {
      const double exact = 0.5 * a * row.time * row.time;
      if (exact < 0.01) continue;
      worst = std::max(worst, std::abs(row.displacement.dot(along.along) - exact) / exact);
    }
    EXPECT_LT(worst, kTolerance) << label;
    std::cout << "[measured] " << label << ": displacement error " << worst << " against g (1 - rho_w/rho)(...)\n";
  }
}

// A block half under water on a level base carries N = W - B (its weight less the buoyancy
// of its submerged half): the uplift on its base, a face in contact, is what takes B off.
// N is read through Coulomb friction: sent sliding at v0 it stops after
// v0^2 / (2 tan(phi) N / m); the side faces' pressures cancel.
TEST_P(Water, AHalfSubmergedBlockPressesOnItsBaseWithItsWeightLessItsBuoyancy) {
  const Integrator integrator = GetParam();
  for (const double draft : {0.5, 0.25}) {
    Scene s = base_scene(2.5, 1.0e-3, 0.01, integrator);
    Interface face;
    face.name = "base";
    face.friction_angle = 30.0;
    s.interfaces.push_back(face);
    s.default_interface = 0;
    s.blocks.push_back(block("floor", {{-5, -2}, {40, -2}, {40, 0}, {-5, 0}}, true));
    BlockInput b = block("block", {{0, 0}, {2, 0}, {2, 1}, {0, 1}}, false);
    b.velocity = Vec2(2.0, 0.0);
    s.blocks.push_back(b);
    s.measure.push_back({"c", {1.0, 0.5}});
    s.water.level = draft;
    RunAudit audit;
    const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
    const std::string label = std::string(name_of(integrator)) + ", draft " + std::to_string(draft);
    expect_contact_physics(r, audit, integrator, label);
    const double weight = kRockDensity * 2.0 * kG, buoyancy = kWater * 2.0 * draft * kG;
    const double normal = weight - buoyancy;
    const double stop = 2.0 * 2.0 / (2.0 * std::tan(30.0 * kDegree) * normal / (kRockDensity * 2.0));
    const double travelled = r.history.back().displacement.x();
    EXPECT_NEAR(travelled, stop, kTolerance * stop) << label << ": N = W - B = " << normal << " N/m";
    std::cout << "[measured] " << label << ": stopped after " << travelled << " m, W - B says " << stop
              << " m (W alone: " << stop * normal / weight << " m)\n";
  }
}

// A block lighter than water floats with its base (rho/rho_w) h below the surface. Released
// at another draft it bobs without damping (nothing in the model takes energy out of
// water), as a harmonic oscillator about that draft: the middle of its highest and lowest
// positions is the equilibrium.
TEST_P(Water, ABlockLighterThanWaterFloatsAtItsDraft) {
  const Integrator integrator = GetParam();
  // Released with its base 0.3 h and 0.6 h under water: it bobs between there and as far
  // past its draft, its sides always cutting the surface (buoyancy linear in the draft).
  for (const auto& [density, width, height, start] :
       {std::tuple{500.0, 2.0, 1.0, 0.3}, std::tuple{800.0, 3.0, 1.0, 0.65}, std::tuple{300.0, 1.5, 0.5, 0.05}}) {
    Scene s = base_scene(3.0, 1.0e-3, 0.002, integrator);
    s.materials.push_back({"wood", density, 5.0e9, 0.25});
    Interface face;
    face.name = "any";
    face.friction_angle = 30.0;
    s.interfaces.push_back(face);
    s.default_interface = 0;
    const double level = 5.0;
    s.blocks.push_back(block("lake bed", {{-10, -3}, {10, -3}, {10, -1}, {-10, -1}}, true));
    s.blocks.push_back(block("raft", box({-0.5 * width, level - start}, {1, 0}, {0, 1}, width, height), false, 1));
    s.measure.push_back({"c", {0.0, level - start + 0.5 * height}});
    s.water.level = level;
    RunAudit audit;
    const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
    const std::string label = std::string(name_of(integrator)) + ", rho " + std::to_string(density) + ", released at draft " + std::to_string(start);
    expect_contact_physics(r, audit, integrator, label);
    double low = INFINITY, high = -INFINITY;
    for (const HistoryRow& row : r.history) {
      low = std::min(low, row.position.y());
      high = std::max(high, row.position.y());
    }
    const double draft = level - (0.5 * (low + high) - 0.5 * height);
    const double expected = density / kWater * height;
    EXPECT_NEAR(draft, expected, kTolerance * expected) << label;
    std::cout << "[measured] " << label << ": draft " << draft << " m against (rho/rho_w) h = " << expected << " m\n";
  }
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Water, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

}  // namespace
}  // namespace ddafit
