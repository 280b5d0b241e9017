// Thermal pressurization of a shear band (forward/contact/laws/thermal_pressurization.hpp),
// checked against two independent statements of its physics:
// - without diffusion the band's excess pore pressure takes the strength down as
//   exp(-d / L), L = rho c h / (tan(phi_p) Lambda): a block on an incline of flush fixed
//   blocks (joints across its path, so the band's column must travel with the face) follows
//   an RK4 integration of d'' = g (sin a - cos a tan(phi_p) exp(-d / L)) within 1 %, both solvers;
// - at a prescribed constant slip rate V on a band much thinner than the diffusion lengths,
//   the shear stress follows Rice's (2006) slip-on-a-plane solution
//   tau / (f sigma') = exp(d / L*) erfc(sqrt(d / L*)), L* = (4/f^2)(rho c/Lambda)^2
//   (sqrt(alpha_hy) + sqrt(alpha_th))^2 / V, within 2 % over d from 0.1 L* to 10 L*.
#include "forward/contact/laws/thermal_pressurization.hpp"
#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

constexpr double kG = 9.81;

struct Adiabatic {
  double slope, friction;  // deg
  double length_scale;     // L, m
  double speed;            // initial, m/s
  double slider;           // length, m
};

// Distance down the slope at `times` by RK4 (slope_scene.hpp) of the exponential limit.
std::vector<double> rk4_adiabatic(const Adiabatic& a, const std::vector<double>& times) {
  const double sa = std::sin(a.slope * kDegree), ca = std::cos(a.slope * kDegree);
  const double mu_p = std::tan(a.friction * kDegree);
  return rk4_slide([&](double d, double) { return kG * (sa - ca * mu_p * std::exp(-d / a.length_scale)); }, a.speed,
                   times);
}

class ThermalPressurization : public ::testing::TestWithParam<Integrator> {};

TEST_P(ThermalPressurization, WithoutDiffusionABlockOnAnInclineFollowsTheExponentialLimit) {
  const Integrator integrator = GetParam();
  const Adiabatic cases[] = {
      {32.0, 30.0, 0.2, 0.0, 1.2},   // steeper than phi_p: slides from rest, then faster
      {20.0, 25.0, 0.5, 2.0, 2.0},   // gentler: slows at first, until the band has pressurized
      {35.0, 35.0, 0.05, 0.5, 0.8},  // at phi_p, sent on at 0.5 m/s, a short L
  };
  for (const Adiabatic& a : cases) {
    Crossing c;
    c.slope = a.slope;
    c.friction = a.friction;
    c.speed = a.speed;
    c.length = a.slider;
    c.height = 0.5;
    c.front_gap = 0.02;
    c.law = FrictionLaw::ThermalPressurization;
    Scene s = crossing_scene(c, integrator);
    Interface& band = s.interfaces[0];
    band.thermal_diffusivity = band.hydraulic_diffusivity = 0.0;
    band.band_thickness = 2e-3;
    band.heat_capacity = 2.7e6;
    band.pressurization_factor = band.heat_capacity * band.band_thickness / (std::tan(a.friction * kDegree) * a.length_scale);
    RunAudit audit;
    const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
    const std::string label = describe(c, integrator) + ", L " + std::to_string(a.length_scale) + " m";
    expect_contact_physics(r, audit, integrator, label);
    const SlideError e = slide_error(r, Slope(a.slope), [&](const std::vector<double>& t) { return rk4_adiabatic(a, t); });
    EXPECT_GT(e.final_distance, 4.0 * a.length_scale) << label << ": the band must have weakened";
    EXPECT_LT(e.worst, 0.01) << label << ": worst at t = " << e.when << " s";
    const double worst = e.worst;
    std::cout << "[measured] " << label << ": displacement error " << worst << " against RK4 of the exponential limit\n";
  }
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, ThermalPressurization,
                         ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const auto& info) { return std::string(name_of(info.param)); });

// The law alone, driven at a constant slip rate on a band 1 um thick (its adiabatic length
// rho c h / (f Lambda) is 1e-3 L*): Rice's slip-on-a-plane solution, two diffusivity ratios
// and two slip rates.
TEST(ThermalPressurizationLaw, AtAConstantSlipRateTheStressFollowsRicesSolutionOnAPlane) {
  struct Drive {
    double alpha_th, alpha_hy, rate;
  };
  for (const Drive& drive : {Drive{7e-7, 4e-6, 1.0}, Drive{1e-6, 1e-7, 0.3}, Drive{5e-7, 5e-7, 3.0}}) {
    Interface face;
    face.friction_angle = 31.0;
    face.law = FrictionLaw::ThermalPressurization;
    face.heat_capacity = 2.7e6;
    face.pressurization_factor = 1.0e5;
    face.thermal_diffusivity = drive.alpha_th;
    face.hydraulic_diffusivity = drive.alpha_hy;
    const double f = std::tan(face.friction_angle * kDegree), sigma = 5.0e6;
    const double root = std::sqrt(drive.alpha_hy) + std::sqrt(drive.alpha_th);
    const double l_star = 4.0 / (f * f) * std::pow(face.heat_capacity / face.pressurization_factor, 2) * root * root / drive.rate;
    face.band_thickness = 1e-3 * l_star * f * face.pressurization_factor / face.heat_capacity;
    const double end = 10.0 * l_star / drive.rate;
    const laws::DiffusionGrid grid = laws::make_diffusion_grid(face, end);
    std::vector<double> column;
    laws::start_column(grid, column);
    const double dt = 1e-4 * l_star / drive.rate;
    double slip = 0.0, excess = 0.0, worst = 0.0;
    double next_check = 0.1 * l_star;
    while (slip < 10.0 * l_star * (1.0 + 1e-9)) {
      const double mu = laws::thermal_pressurization(face, {slip, drive.rate, 0.0, sigma, excess});
      excess = laws::advance_column(face, grid, mu * sigma * drive.rate * dt, dt, column);
      slip += drive.rate * dt;
      if (slip >= next_check) {
        const double x = slip / l_star;
        const double rice = std::exp(x) * std::erfc(std::sqrt(x));
        const double tau = laws::thermal_pressurization(face, {slip, drive.rate, 0.0, sigma, excess}) / f;
        worst = std::max(worst, std::abs(tau - rice) / rice);
        next_check *= 1.1;
      }
    }
    EXPECT_LT(worst, 0.02) << "alpha_th " << drive.alpha_th << ", alpha_hy " << drive.alpha_hy << ", V " << drive.rate;
    std::cout << "[measured] alpha_th " << drive.alpha_th << ", alpha_hy " << drive.alpha_hy << ", V " << drive.rate
              << " m/s, L* " << l_star << " m, " << grid.width.size() << " cells: worst error " << worst
              << " against Rice (2006) over 0.1-10 L*\n";
  }
}

}  // namespace
}  // namespace ddafit
