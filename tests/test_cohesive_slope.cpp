// Bonds on a jointed slope (contact_law.hpp: |T| <= tan(phi) N + c l_c and N >= -T_s l_c while
// bonded): a block held from sliding by cohesion, and a column held from toppling by tensile
// strength (further down). The block, limit equilibrium: it stays while
// c L >= W (sin a - cos a tan phi), W = rho g L H (per metre), and once the bond is gone it
// slides as seed Eq. 4 says. Asserted as a class:
// four slopes and frictions, four blocks (0.8 to 8 m long, never narrower than twice their
// height, so none topples on the 50 deg slope), joints every 0.3, 1 and 2.5 m under them, steps
// of 1 ms x 4, 5 ms x 4 and 10 ms x 3 (the Vajont scenes'), both solvers.
//
// Found 2026-12-03 (model revision .12.03.3): at 1 ms steps, with 1.5 times the cohesion that
// holds it, 20 of 24 blocks slid away (at 3 times, 10 of the 22 that could not topple). A bond went as soon as one point's force reached
// its cap, although where a block rests on several points the share each carries is the
// solver's to choose: the point at its cap passed its load to the others, whose bonds went
// next. The implicit solver broke them while settling, where the block's own elastic strain
// loads the points at its ends most. And a point at a joint's end, where two base blocks'
// manifolds meet, kept one copy of two but only that copy's half of the bonded length, so a
// block over joints 0.3 m apart was held by about half its bond. Now a bond goes once its
// point has slid (or opened) at its strength by more than the contact slop
// (contact_law.hpp, wear_bond), and the copy kept carries both halves (collide.cpp,
// drop_shared_corners).
//
// Tolerances and why:
//   - 1.5 times the holding cohesion: the block moves less than 0.1 mm in 1.5 s (measured:
//     20 um at most, the implicit solver's 8 x 4 m block at 50 deg, its elastic strain; a block
//     that lets go moves metres). Between the limit and about 1.3 times whether it holds
//     depends on how a solver shares the load among the points (the implicit solver's 8 m
//     block at 50 deg let go at 1.25 times, the substep solver's blocks held at 1.1 times).
//   - 0.8 times: the block slides, and after the bond is gone at seed Eq. 4's acceleration
//     (friction alone): the second difference of its displacement at 0.5, 1 and 1.5 s within
//     1 % of Eq. 4 (measured within 1e-4), and its run at 1.5 s at least 95 % of Eq. 4's from
//     t = 0 (measured 97.9-99.9 %: until its bond goes, the block accelerates at a fifth of
//     Eq. 4's rate, over the slop).
#include <cstdio>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

// The cohesion (Pa) that just holds a block of height H on the slope:
// c L = W (sin a - cos a tan phi), W = rho g L H.
double holding_cohesion(const Crossing& c) {
  return kRockDensity * 9.81 * c.height *
         (std::sin(c.slope * kDegree) - std::cos(c.slope * kDegree) * std::tan(c.friction * kDegree));
}

struct StepSetting {
  double step;
  int substeps;
};
constexpr StepSetting kSteps[] = {{kStep, 4}, {0.005, 4}, {0.01, 3}};

// The class: every slope with every joint spacing, the blocks rotated through them.
std::vector<Crossing> bonded_blocks() {
  const double slopes[][2] = {{28, 18}, {20, 12}, {40, 25}, {50, 30}};
  const double blocks[][2] = {{1.2, 0.6}, {0.8, 0.4}, {3.0, 0.8}, {8.0, 4.0}};
  std::vector<Crossing> out;
  int n = 0;
  for (const auto& slope : slopes)
    for (const double spacing : {0.3, 1.0, 2.5}) {
      out.push_back(sweep_case(slope, blocks[n % 4], spacing, n));
      ++n;
    }
  return out;
}

struct BondedRun {
  SimulationResult result;
  std::string label;
  double along(double t, const Crossing& c) const {  // displacement down the slope at output time t
    const HistoryRow* best = &result.history.front();
    for (const HistoryRow& h : result.history)
      if (std::abs(h.time - t) < std::abs(best->time - t)) best = &h;
    return best->displacement.dot(Slope(c.slope).along);
  }
};

BondedRun run_bonded(const Crossing& c, double strength, const StepSetting& step, Integrator integrator) {
  Scene s = crossing_scene(c, integrator);
  s.interfaces[0].cohesion = strength * holding_cohesion(c);
  s.max_step = step.step;
  s.options.substeps = step.substeps;
  BondedRun r{simulate(s), describe(c, integrator) + ", cohesion " + std::to_string(strength) +
                               " x the holding one, step " + std::to_string(step.step) + " s x " +
                               std::to_string(step.substeps)};
  EXPECT_EQ(r.result.summary.status, RunStatus::Completed) << r.label << ": " << r.result.summary.message;
  return r;
}

class CohesiveSlope : public ::testing::TestWithParam<Integrator> {};

TEST_P(CohesiveSlope, ABlockBondedByMoreThanTheHoldingCohesionStays) {
  double most = 0.0;
  std::string worst;
  for (const StepSetting& step : kSteps)
    for (const Crossing& c : bonded_blocks()) {
      const BondedRun r = run_bonded(c, 1.5, step, GetParam());
      const double moved = r.result.summary.points.front().max_total_displacement;
      EXPECT_LT(moved, 1e-4) << r.label;
      if (moved > most) most = moved, worst = r.label;
    }
  std::printf("[measured] bonded blocks at 1.5 x the holding cohesion: moved %.3g m at most (%s)\n", most,
              worst.c_str());
}

TEST_P(CohesiveSlope, ABlockBondedByLessThanTheHoldingCohesionSlidesAsSeedEq4) {
  double worst_acceleration = 0.0, least_run = 1e30;
  for (const StepSetting& step : kSteps)
    for (const Crossing& c : bonded_blocks()) {
      const BondedRun r = run_bonded(c, 0.8, step, GetParam());
      if (r.result.history.empty() || r.result.history.back().time < 1.5 - 1e-9) continue;
      const double a = eq4_acceleration(c.slope, c.friction);
      const double second_difference = (r.along(1.5, c) - 2.0 * r.along(1.0, c) + r.along(0.5, c)) / 0.25;
      const double acceleration_error = std::abs(second_difference - a) / a;
      const double run = r.along(1.5, c) / (0.5 * a * 1.5 * 1.5);
      EXPECT_LT(acceleration_error, 0.01) << r.label << ": " << second_difference << " against " << a << " m/s2";
      EXPECT_GT(run, 0.95) << r.label;
      worst_acceleration = std::max(worst_acceleration, acceleration_error);
      least_run = std::min(least_run, run);
    }
  std::printf("[measured] bonded blocks at 0.8 x the holding cohesion: acceleration within %.3g of seed Eq. 4, "
              "run at 1.5 s at least %.4f of Eq. 4's\n",
              worst_acceleration, least_run);
}

// Toppling: a column narrower than the slope lets stand (L / H < tan a) held up by the tensile
// strength of its base. About its downhill corner gravity turns it with
// M = W (sin a H / 2 - cos a L / 2); the bond's most, every point of the base at its tension
// cut-off, is T_s L^2 / 2. Friction (phi > a) keeps it from sliding, and there is no cohesion,
// so a point in tension carries no shear.
double holding_tensile_strength(const Crossing& c) {
  const double a = c.slope * kDegree;
  const double weight = kRockDensity * 9.81 * c.length * c.height;
  return 2.0 * weight * (std::sin(a) * 0.5 * c.height - std::cos(a) * 0.5 * c.length) / (c.length * c.length);
}

// Columns on three slopes {a, phi}, four sizes {L, H}, standing on one base block (5 m) or
// across joints 0.2 m apart; those that would not topple unbonded (L / H >= 0.9 tan a) are left
// out. 20 columns.
std::vector<Crossing> bonded_columns() {
  const double slopes[][2] = {{30, 40}, {20, 35}, {40, 50}};
  const double columns[][2] = {{0.5, 1.5}, {0.3, 1.2}, {2.0, 6.0}, {1.0, 4.0}};
  std::vector<Crossing> out;
  for (const auto& slope : slopes)
    for (const auto& column : columns)
      for (const double spacing : {0.2, 5.0}) {
        const Crossing c = sweep_case(slope, column, spacing, 0);
        if (c.length / c.height < 0.9 * std::tan(c.slope * kDegree)) out.push_back(c);
      }
  return out;
}

// Largest displacement of the column's measure point over the run, m.
double column_moved(const Crossing& c, double strength, Integrator integrator, std::string& label) {
  Scene s = crossing_scene(c, integrator);
  s.interfaces[0].tensile_strength = strength * holding_tensile_strength(c);
  const SimulationResult r = simulate(s);
  label = describe(c, integrator) + ", tensile strength " + std::to_string(strength) + " x the holding one";
  EXPECT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  return r.summary.points.front().max_total_displacement;
}

// Found 2026-12-03 (model revision .12.03.3): the implicit solver let 10 of the 20 columns topple
// at 1.5 times the holding strength, those standing across joints: its elastic springs load the
// base's uphill point most, and a point past the cut-off opened and pulled no more. An open point
// still bonded now pulls with T_s l_c until it has opened by the slop (assemble.cpp); the
// substep solver's impulses are capped there already.
//   - 1.5 times (and 1.2: every column holds on both solvers, measured): the column moves less
//     than 0.1 mm (measured 3.4 um at most; one that topples moves metres);
//   - 0.7 times: it topples, its measure point (at mid-height) moving more than a quarter of its
//     height (measured 0.375 of it at least, a column coming to rest on its side).
TEST_P(CohesiveSlope, AColumnBondedByMoreThanTheHoldingTensileStrengthStands) {
  double most = 0.0;
  for (const Crossing& c : bonded_columns()) {
    std::string label;
    const double moved = column_moved(c, 1.5, GetParam(), label);
    EXPECT_LT(moved, 1e-4) << label;
    most = std::max(most, moved);
  }
  std::printf("[measured] %zu bonded columns at 1.5 x the holding tensile strength: moved %.3g m at most\n",
              bonded_columns().size(), most);
}

TEST_P(CohesiveSlope, AColumnBondedByLessThanTheHoldingTensileStrengthTopples) {
  double least = 1e30;
  for (const Crossing& c : bonded_columns()) {
    std::string label;
    const double moved = column_moved(c, 0.7, GetParam(), label);
    EXPECT_GT(moved, 0.25 * c.height) << label;
    least = std::min(least, moved / c.height);
  }
  std::printf("[measured] bonded columns at 0.7 x the holding tensile strength: moved %.3g of their height at least\n",
              least);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, CohesiveSlope, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& i) { return name_of(i.param); });

}  // namespace
}  // namespace ddafit
