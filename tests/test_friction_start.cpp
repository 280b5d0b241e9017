// Blocks thrown onto a jointed floor or slope, which friction stops while it degrades (seed
// Eq. 2-3): how far they run is decided in their first steps, where d_c (1 % of the block's
// length) may be crossed within one step. Found 2026-12-06 by a black-box sweep of slabs
// stopping on jointed bases through `ddafit simulate`: a 0.5 m block thrown at 1 m/s onto a
// floor at 10 ms stopped 3.1-3.7 % short on the implicit solver.
//
// Two causes, mended by model revision 2026-12-06.22 (forward/contact/slip_history.hpp,
// predict_first_slip; contact_law.hpp, friction_coefficient):
//   - a face that had not slid yet took its peak friction for its whole first (sub)step, though
//     its blocks already slid past each other: it now predicts that step's slip from their speed;
//   - a step whose slip crosses d_c took the law at its midpoint, where the bilinear law bends:
//     it now takes the mean of the law over the step's slip.
//
// The class: blocks 0.05-2 m long and 0.3 as thick, thrown at 1 and 4 m/s down or up slopes of
// 0-20 deg at phi 30-40 deg losing 10 deg over d_c, over joints every 0.37 and 1.6 lengths, at
// 2 ms x 4 and 10 ms x 3, both solvers. Reference: where the block stops, from the work of
// friction and gravity along its path (seed Eq. 2-3 integrated in closed form, below).
// Tolerance 1 % of that distance, test_joint_crossing.cpp's, and the contact audits of
// contact_scene_audit.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

constexpr double kStopTolerance = 0.01;
constexpr double kGravity = 9.81;

struct Throw {
  Crossing c;         // c.speed > 0 down the slope, < 0 up it
  double step = 0.002;
  int substeps = 4;
};

// The work friction does per unit weight and cos(alpha) over a path of s (m): the integral of
// tan(phi) with phi falling linearly by i over d_c (seed Eq. 3),
// (d_c / i) ln(cos phi(s) / cos phi_p), then tan(phi_r) beyond d_c.
double friction_path(const Crossing& c, double s) {
  const double dc = c.dc_ratio * c.length, peak = c.friction * kDegree, drop = c.roughness * kDegree;
  const double residual = peak - drop;
  if (drop <= 0.0) return s * std::tan(peak);
  const double before = std::min(s, dc);
  const double phi = peak - drop * before / dc;
  return dc / drop * std::log(std::cos(phi) / std::cos(peak)) + std::max(s - dc, 0.0) * std::tan(residual);
}

// Where the block stops, m along the slope (signed as c.speed): v0^2 / 2 = g (cos a F(s) -/+ sin a s).
double stop_distance(const Crossing& c) {
  const double a = c.slope * kDegree, sign = c.speed > 0.0 ? 1.0 : -1.0;
  const auto work = [&](double s) {
    return kGravity * (std::cos(a) * friction_path(c, s) - sign * std::sin(a) * s);
  };
  const double energy = 0.5 * c.speed * c.speed;
  double low = 0.0, high = 1.0;
  while (work(high) < energy) high *= 2.0;
  for (int k = 0; k < 200; ++k) (work(0.5 * (low + high)) < energy ? low : high) = 0.5 * (low + high);
  return sign * 0.5 * (low + high);
}

// crossing_scene with the ground carried up the slope past where a block thrown up it stops,
// run until well after it stops, and every corner to the nanometre as a scene file gives it.
Scene throw_scene(const Throw& t, Integrator integrator) {
  const Crossing& c = t.c;
  Crossing down = c;  // crossing_scene lays its ground for a block going down the slope
  down.speed = std::abs(c.speed);
  Scene s = crossing_scene(down, integrator);
  s.blocks.back().velocity = c.speed * Slope(c.slope).along;
  s.max_step = t.step;
  s.options.substeps = t.substeps;
  const double a = c.slope * kDegree, residual = (c.friction - c.roughness) * kDegree;
  const double slowest = kGravity * (std::cos(a) * std::tan(residual) - (c.speed > 0.0 ? 1.0 : -1.0) * std::sin(a));
  s.duration = 1.2 * std::abs(c.speed) / slowest + 0.1;
  const Slope slope(c.slope);
  const int above = static_cast<int>(std::ceil((std::abs(stop_distance(c)) + 2.0 * c.length) / c.spacing));
  std::vector<BlockInput> ground;
  for (int j = -above; j < 0; ++j) {
    const double s0 = j * c.spacing, s1 = s0 + c.spacing;
    ground.push_back(block("base_up_" + std::to_string(-j),
                           {slope.at(s0, 0), slope.at(s0, -1), slope.at(s1, -1), slope.at(s1, 0)}, true, 0, "base"));
  }
  s.blocks.insert(s.blocks.begin(), ground.begin(), ground.end());
  for (BlockInput& b : s.blocks)
    for (Vec2& p : b.polygon) p = Vec2(std::round(p.x() * 1e9) / 1e9, std::round(p.y() * 1e9) / 1e9);
  return s;
}

// Runs the class on one solver: every run completes, keeps the contact audits, and stops within
// 1 % of the distance the work of friction and gravity gives.
void expect_throws_stop_where_friction_says(const std::vector<Throw>& throws, Integrator integrator) {
  double worst = 0.0;
  std::string worst_case;
  for (const Throw& t : throws) {
    const Scene scene = throw_scene(t, integrator);
    char text[80];
    std::snprintf(text, sizeof text, ", %g ms x %d", 1e3 * t.step, t.substeps);
    const std::string label = describe(t.c, integrator) + text;
    RunAudit audit;
    const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
    expect_contact_physics(r, audit, integrator, label);
    if (r.summary.status != RunStatus::Completed || r.history.empty()) continue;
    const double expected = stop_distance(t.c);
    const double ran = r.history.back().displacement.dot(Slope(t.c.slope).along);
    const double error = std::abs(ran - expected) / std::abs(expected);
    EXPECT_LT(error, kStopTolerance) << label << ": stopped at " << ran << " m, friction's work says " << expected;
    if (error > worst) worst = error, worst_case = label;
  }
  std::printf("[measured] %s, blocks thrown onto jointed ground: %zu runs, worst %.2g of the stopping distance (%s)\n",
              name_of(integrator).c_str(), throws.size(), worst, worst_case.c_str());
}

class FrictionStart : public ::testing::TestWithParam<Integrator> {};

// 72 runs a solver. Before revision .22: the implicit solver up to 3.7 % short.
TEST_P(FrictionStart, AThrownBlockStopsWhereTheWorkOfFrictionSays) {
  std::vector<Throw> throws;
  int n = 0;
  for (const auto& [slope, friction] : {std::pair{0.0, 30.0}, {10.0, 35.0}, {20.0, 40.0}})
    for (const double direction : {1.0, -1.0})
      for (const double length : {0.05, 0.5, 2.0})
        for (const double speed : {1.0, 4.0})
          for (const auto& [step, substeps] : {std::pair{0.002, 4}, {0.01, 3}}) {
            Throw t;
            t.c.slope = slope, t.c.friction = friction, t.c.roughness = 10.0;
            t.c.length = length, t.c.height = 0.3 * length;
            t.c.spacing = (n % 3 == 1 ? 1.6 : 0.37) * length;
            t.c.front_gap = 0.3 * t.c.spacing;
            t.c.speed = direction * speed;
            t.step = step, t.substeps = substeps;
            throws.push_back(t);
            ++n;
          }
  expect_throws_stop_where_friction_says(throws, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Stopping, FrictionStart, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

}  // namespace
}  // namespace ddafit
