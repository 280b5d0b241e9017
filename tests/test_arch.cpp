// Semicircular masonry arches of voussoirs on a fixed floor, no cohesion, friction 40 deg: Heyman's
// minimum thickness (J. Heyman, "The safety of masonry arches", Int. J. Mech. Sci. 11, 1969): a
// semicircular arch of mean radius R stands under its own weight only if its thickness t is at
// least 0.1075 R (four hinges form at thinner ones; with 40 deg of friction no joint slides).
// Arches of 9 and 15 voussoirs, R 1 and 10 m, t/R 0.08 (below the limit), 0.15 and 0.25; the
// implicit solver at 1 and 10 ms, the substep solver at 1, 2 and 5 ms x 4 and 10 ms x 6: 72 runs.
// Found 2026-12-06 by a black-box sweep through `ddafit simulate`, which met the limit on both
// solvers.
//
// Tolerances and why:
//   - t/R 0.15 and 0.25 stand: the crown moves less than 1e-3 R over 2 sqrt(R) s (measured 1e-4 R
//     at most, the joints' elastic closure; a collapsing arch's crown falls most of R);
//   - t/R 0.08 collapses: the crown moves more than half of R within that time (measured 0.95 R);
//   - the checks every contact scene shares (contact_scene_audit.hpp: completed, the energy
//     budget of 1e-6 of the energy in play plus the elastic floor, no pass-through, overlaps under
//     1 % of the smaller block) on the implicit solver and on the substep solver at 1 ms. KNOWN
//     LIMIT: beyond 1 ms the substep solver passes that budget (completing under its own audit's
//     5 %): collapsing arches by up to 0.2 % of the energy in play (37.5 J/m of 20 279, 15
//     voussoirs of R 10 m, 5 ms x 4), standing ones by rising 6e-6-4e-5 R as their joints open
//     from the quiet start's overlaps (docs/theory.md §8, "Energy audit", R); there only the
//     outcome is asserted.
// At 10 ms the substep solver takes 6 substeps here: at its default 4 (and at 3) the
// 15-voussoir 1 m arch at t/R 0.25 stops with the energy audit's diagnosis, which names the
// substeps to raise (the known defect at the end).
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/contact_scene_audit.hpp"

namespace ddafit {
namespace {

struct Arch {
  int voussoirs;
  double radius, thickness_ratio, step;
};

// Largest displacement of the crown over the run, as a share of R; -1 if the run did not complete.
// `strict`: the shared checks of contact_scene_audit.hpp as well, which require the run to
// complete (else the caller asserts that, from the return).
double crown_moved(const Arch& a, Integrator integrator, int substeps, bool strict) {
  const double R = a.radius, t = a.thickness_ratio * R;
  Scene s = base_scene(2.0 * std::sqrt(R), a.step, 0.05, integrator);
  s.options.substeps = substeps;
  s.default_interface = add_interface(s, "joint", 40.0);
  const Vec2 x(1.0, 0.0), y(0.0, 1.0);
  s.blocks.push_back(block("floor", box({-R - t - 2.0, -1.0}, x, y, 2.0 * (R + t + 2.0), 1.0), true));
  const double inner = R - 0.5 * t, outer = R + 0.5 * t;
  for (int k = 0; k < a.voussoirs; ++k) {
    const double a0 = M_PI * (a.voussoirs - k) / a.voussoirs, a1 = M_PI * (a.voussoirs - k - 1) / a.voussoirs;
    const Vec2 d0(std::cos(a0), std::sin(a0)), d1(std::cos(a1), std::sin(a1));
    const std::string name = std::string("v").append(std::to_string(k));
    s.blocks.push_back(block(name, {inner * d1, outer * d1, outer * d0, inner * d0}, false));
  }
  s.measure.push_back({"crown", {0.0, R}});
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  char label[160];
  std::snprintf(label, sizeof label, "%s: %d voussoirs, R %g m, t/R %g, %g ms x %d", name_of(integrator).c_str(),
                a.voussoirs, R, a.thickness_ratio, 1e3 * a.step, substeps);
  if (strict) expect_contact_physics(r, audit, integrator, label);
  if (r.summary.status != RunStatus::Completed) {
    std::printf("%s: %s\n", label, r.summary.message.c_str());
    return -1.0;
  }
  const double moved = r.summary.points.front().max_total_displacement / R;
  if (a.thickness_ratio > 0.1075)
    EXPECT_LT(moved, 1e-3) << label << ": an arch thicker than Heyman's limit fell";
  else
    EXPECT_GT(moved, 0.5) << label << ": an arch thinner than Heyman's limit stood";
  return moved;
}

class Arches : public ::testing::TestWithParam<Integrator> {};

// The steps a solver is held to the strict energy audit at, and those at which only the outcome
// and the run's own audit are (the substep solver beyond 1 ms: the known limit at the top).
struct StepCase {
  double step;
  int substeps;
  bool strict;
};

TEST_P(Arches, StandAboveHeymansMinimumThicknessAndFallBelowIt) {
  const bool implicit = GetParam() == Integrator::Implicit;
  const std::vector<StepCase> steps = implicit ? std::vector<StepCase>{{0.001, 4, true}, {0.01, 4, true}}
                                               : std::vector<StepCase>{{0.001, 4, true}, {0.002, 4, false},
                                                                       {0.005, 4, false}, {0.01, 6, false}};
  double most_standing = 0.0, least_falling = 1e30;
  int runs = 0;
  for (const int n : {9, 15})
    for (const double R : {1.0, 10.0})
      for (const double ratio : {0.08, 0.15, 0.25})
        for (const StepCase& step : steps) {
          const double moved = crown_moved({n, R, ratio, step.step}, GetParam(), step.substeps, step.strict);
          ++runs;
          EXPECT_GE(moved, 0.0) << "the run did not complete (printed above)";
          if (moved < 0.0) continue;
          if (ratio > 0.1075) most_standing = std::max(most_standing, moved);
          else least_falling = std::min(least_falling, moved);
        }
  EXPECT_EQ(runs, implicit ? 24 : 48);
  std::printf("[measured] %d arches, %s: crowns of standing arches moved %.3g R at most, of falling ones %.3g R at "
              "least\n",
              runs, name_of(GetParam()).c_str(), most_standing, least_falling);
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Arches, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& i) { return name_of(i.param); });

// KNOWN DEFECT (found 2026-12-06, revision .18): at 10 ms with the default 4 substeps (and with
// 3) the substep solver stops the 15-voussoir arch of R 1 m at t/R 0.25 with the energy audit's
// diagnosis at 0.89 s (1.2 J/m of kinetic energy more than gravity's work; its crown 1 mm down),
// as its tall columns sway (docs/theory.md §13, "Tall columns sway": sweeps unconverged over a
// long chain of contacts); at 6 substeps it stands.
TEST(Arches, DISABLED_StandAtTenMillisecondsWithTheDefaultSubstepsSubstep) {
  for (const int n : {9, 15})
    for (const double R : {1.0, 10.0})
      for (const double ratio : {0.08, 0.15, 0.25})
        EXPECT_GE(crown_moved({n, R, ratio, 0.01}, Integrator::Substep, 4, false), 0.0)
            << "the run did not complete (printed above)";
}

}  // namespace
}  // namespace ddafit
