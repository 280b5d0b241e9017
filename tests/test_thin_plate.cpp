// Blocks dropped onto a thin plate lying on the ground: a 1 m plate 1, 5 and 25 cm thick,
// one 1 m block or a stack of four dropped 0.1 and 1 m onto it, at 1 and 10 ms, both solvers:
// 48 runs. A plate much thinner than it is long is where a DDA block's shear strain and its
// rotation move its faces alike (the mass matrix couples r0 and gamma by (S_xx - S_yy) / 2).
// Found 2026-12-06 by black-box sweeps through `ddafit simulate`: the implicit solver stopped
// 3 of 32 drops like these (plates of 1, 5, 10 and 25 cm; all three on the 1 cm plate) at the
// impact with "contacts are creating energy", and 8 of 24 drops of a stack onto 1-20 mm plates.
// The plate squeezed between the stack and the ground rang in its shear mode (at 0.14 s:
// rotation rate -49.75 rad/s, shear rate 99.5 /s, faces moving at centimetres a second), and the
// audit counted the rotation alone, 1/2 I w^2 = 2784 J/m against 2650 J/m of gravity's work.
// The audit now counts 1/2 V^T M V with the block's whole mass matrix
// (forward/common/energy_check.cpp, model revision 2026-12-06.17).
//
// Tolerances and why:
//   - the checks every contact scene shares (contact_scene_audit.hpp): completed, the energy
//     budget (1e-6 of the energy in play plus the elastic floor), no pass-through, overlaps
//     under 1 % of the smaller block;
//   - the plate stays where it lies: its centroid moves less than a tenth of its thickness
//     (a plate squeezed out from under the stack moves by its length);
//   - the dropped blocks land on it: the top block's centroid ends within 1 cm of its drop
//     (not asserted for the implicit solver's 1 cm plate: the known defect at the end).
#include <cstdio>

#include "tests/contact_scene_audit.hpp"

namespace ddafit {
namespace {

struct PlateDrop {
  double thickness, drop, step;
  int stacked;
};

// `landing` false: only the shared checks (the known defect below).
void expect_landing_on_the_plate(const PlateDrop& d, Integrator integrator, double& worst_plate, double& worst_top,
                                 bool landing = true) {
  Scene s = base_scene(1.0, d.step, 0.01, integrator);
  s.options.substeps = 3;
  s.default_interface = add_interface(s, "joint", 30.0);
  const Vec2 x(1.0, 0.0), y(0.0, 1.0);
  s.blocks.push_back(block("ground", box({-2.0, -1.0}, x, y, 5.0, 1.0), true));
  s.blocks.push_back(block("plate", box({0.0, 0.0}, x, y, 1.0, d.thickness), false));
  double base = d.thickness + d.drop;
  for (int k = 0; k < d.stacked; ++k, base += 1.0)
    s.blocks.push_back(block(std::string("b").append(std::to_string(k)), box({0.0, base}, x, y, 1.0, 1.0), false));
  s.measure.push_back({"plate", {0.5, 0.5 * d.thickness}});
  s.measure.push_back({"top", {0.5, base - 0.5}});
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  char label[160];
  std::snprintf(label, sizeof label, "%s: %d block(s) dropped %g m onto a %g m plate, %g ms",
                name_of(integrator).c_str(), d.stacked, d.drop, d.thickness, 1e3 * d.step);
  expect_contact_physics(r, audit, integrator, label);
  if (r.summary.status != RunStatus::Completed || !landing) return;
  const Vec2 plate = r.history.end()[-2].displacement, top = r.history.back().displacement;
  EXPECT_LT(plate.norm(), 0.1 * d.thickness) << label;
  EXPECT_NEAR(-top.y(), d.drop, 0.01) << label;
  worst_plate = std::max(worst_plate, plate.norm() / d.thickness);
  worst_top = std::max(worst_top, std::abs(-top.y() - d.drop));
}

class ThinPlate : public ::testing::TestWithParam<Integrator> {};

TEST_P(ThinPlate, BlocksDroppedOntoAThinPlateLandOnItWithoutCreatingEnergy) {
  double worst_plate = 0.0, worst_top = 0.0;
  int runs = 0;
  for (const double thickness : {0.01, 0.05, 0.25})
    for (const double drop : {0.1, 1.0})
      for (const int stacked : {1, 4})
        for (const double step : {0.001, 0.01}) {
          const bool known_defect = GetParam() == Integrator::Implicit && thickness < 0.02;  // below
          expect_landing_on_the_plate({thickness, drop, step, stacked}, GetParam(), worst_plate, worst_top,
                                      !known_defect);
          ++runs;
        }
  EXPECT_EQ(runs, 24);
  std::printf("[measured] %d drops onto thin plates, %s: plate moved %.3g of its thickness at most, top block %.3g m "
              "off its drop at most\n",
              runs, name_of(GetParam()).c_str(), worst_plate, worst_top);
}

// KNOWN DEFECT (found 2026-12-06, revision .17): on the implicit solver a stack of four 1 m blocks
// dropped 1 m onto the 1 cm plate bounces: its top block rises 0.33 m after the landing (2.4 cm
// on the 5 cm plate, 4 mm on the 25 cm one; the substep solver's stacks do not rise), and at 1 s
// it is still 2.4 cm above its rest with the plate pushed 2.7 mm aside. The energy audit holds:
// the plate's shear mode, stiff and light, takes the blow and gives it back to the stack (docs/
// theory.md, Known limits (a)). The shared checks above hold for these runs.
TEST(ThinPlate, DISABLED_AStackDroppedOntoACentimetrePlateLandsOnItImplicit) {
  double worst_plate = 0.0, worst_top = 0.0;
  for (const double drop : {0.1, 1.0})
    for (const int stacked : {1, 4})
      for (const double step : {0.001, 0.01})
        expect_landing_on_the_plate({0.01, drop, step, stacked}, Integrator::Implicit, worst_plate, worst_top);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, ThinPlate, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& i) { return name_of(i.param); });

}  // namespace
}  // namespace ddafit
