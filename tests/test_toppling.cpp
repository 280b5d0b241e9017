// Goodman & Bray's block on an incline (Hoek & Bray, Rock Slope Engineering): a b x h block
// on a slope of dip alpha and friction phi is stable, slides, topples, or slides and
// topples, as alpha against phi and b / h against tan(alpha) decide. Each case sits well
// inside its region of their chart, and both solvers must show its mode in the first
// 0.2 s of motion (the block's rotation against the slip of its downslope base corner) and
// in its final state. The landing of a toppling block -- a corner striking the plane -- is
// where a vertex-edge penalty scheme threw a block off at 50 m/s (field notes).
//
// Tolerances and why:
//   - at rest: rotation under 1e-3 rad and slip under 1 mm (elastic settling is micrometres);
//   - sliding: the slip in 0.2 s within 5 % of seed Eq. 4 (the joint-crossing tests hold
//     1 %; here the block is tall and the 0.2 s include the start-up of its contacts);
//   - toppling: the analytic rotation about the corner in 0.2 s is 0.054 rad (the moment of
//     the weight about the corner over its moment of inertia there); over 0.02 rad is
//     toppling, far above any rocking of a block at rest;
//   - the final states: lying on its long face (rotated 90 deg within 10 deg), and slid
//     metres (slide and topple) or not (topple: friction 40 deg holds it once it lies flat).
#include "tests/contact_scene_audit.hpp"

namespace ddafit {
namespace {

constexpr double kEarly = 0.2;  // s: the "first motion" window

struct BlockOnIncline {
  const char* mode;
  double slope, friction;  // alpha, phi (deg)
  double width, height;    // b, h (m)
};

// Stable: phi > alpha, b/h > tan alpha. Slide: phi < alpha, b/h > tan alpha. Topple:
// phi > alpha, b/h < tan alpha. Slide and topple: phi < alpha, b/h < tan alpha (the field
// notes' case: may start as a pure topple and slide once it lands).
const BlockOnIncline kModes[] = {
    {"stable", 20.0, 35.0, 1.0, 1.0},
    {"slide", 35.0, 20.0, 2.0, 1.0},
    {"topple", 25.0, 40.0, 0.25, 1.0},
    {"slide_and_topple", 35.0, 25.0, 0.25, 1.0},
};

struct Motion {
  double rotation = 0.0;  // |angle| turned by the block, rad
  double slip = 0.0;      // of its downslope base corner along the slope, m
};

using ModeParam = std::tuple<Integrator, int>;
class GoodmanBray : public ::testing::TestWithParam<ModeParam> {};

// One block of `c` on its incline, scaled by `scale` (the block and the plane) and run at `step`
// with `substeps` (the substep solver), checked as the comment at the top says; the slips and the
// final slide's bound scale with the block.
void expect_mode(const BlockOnIncline& c, Integrator integrator, double scale, double step,
                 int substeps = SimulationOptions{}.substeps) {
  Scene s = base_scene(3.0, step, 0.01 * std::sqrt(scale), integrator);  // 20 rows in the first-motion window
  s.options.substeps = substeps;
  add_interface(s, "plane", c.friction);
  s.default_interface = 0;
  const Vec2 along(std::cos(c.slope * kDegree), -std::sin(c.slope * kDegree));
  const Vec2 up(-along.y(), along.x());
  const double L = scale;
  const double plane = std::max(20.0 * L, 40.0);  // long enough for the slides of 3 s at any size
  s.blocks.push_back(block("plane", {Vec2::Zero(), plane * along, plane * along - 2.0 * L * up, -2.0 * L * up}, true));
  const Vec2 origin = 2.0 * L * along;  // the block's upslope base corner
  s.blocks.push_back(block("block", box(origin, along, up, c.width * L, c.height * L), false));
  // Two material points: just inside the downslope base corner, and the top upslope corner.
  s.measure.push_back({"corner", origin + (c.width - 0.01) * L * along + 0.01 * L * up});
  s.measure.push_back({"top", origin + 0.01 * L * along + (c.height - 0.01) * L * up});

  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  const std::string label = std::string(c.mode) + " (" + std::to_string(c.slope) + "/" +
                            std::to_string(c.friction) + ", " +
                            std::to_string(c.width) + " x " + std::to_string(c.height) + "), " + name_of(integrator) +
                            ", x" + std::to_string(scale) + ", step " + std::to_string(step);
  expect_contact_physics(r, audit, integrator, label);

  const Vec2 arm0 = s.measure[1].at - s.measure[0].at;
  const auto motion_at = [&](double t) {
    Vec2 corner = Vec2::Zero(), top = Vec2::Zero(), corner_shift = Vec2::Zero();
    for (const HistoryRow& row : r.history) {
      if (row.time > t + 1e-9) break;
      (row.point == 0 ? corner : top) = row.position;
      if (row.point == 0) corner_shift = row.displacement;
    }
    const Vec2 arm = top - corner;
    return Motion{std::abs(std::atan2(cross(Vec2::Zero(), arm0, arm), arm0.dot(arm))), corner_shift.dot(along)};
  };
  // The first-motion window scales as the block's own time, sqrt(L / g): a toppling block turns
  // by the same angle in it at any size.
  const double early_window = kEarly * std::sqrt(L);
  const Motion early = motion_at(early_window), last = motion_at(s.duration);
  const double a = 9.81 * (std::sin(c.slope * kDegree) - std::cos(c.slope * kDegree) * std::tan(c.friction * kDegree));
  const std::string mode = c.mode;
  if (mode == "stable") {
    EXPECT_LT(early.rotation, 1e-3) << label;
    EXPECT_LT(std::abs(early.slip), 1e-3 * L) << label;
    EXPECT_LT(last.rotation, 1e-3) << label;
    EXPECT_LT(std::abs(last.slip), 1e-3 * L) << label;
  } else if (mode == "slide") {
    EXPECT_LT(early.rotation, 1e-3) << label;
    const double eq4 = 0.5 * a * early_window * early_window;
    EXPECT_NEAR(early.slip, eq4, 0.05 * eq4) << label;
    EXPECT_LT(last.rotation, 1e-3) << label;
    EXPECT_GT(last.slip, 0.99 * 0.5 * a * s.duration * s.duration) << label;
  } else {
    EXPECT_GT(early.rotation, 0.02) << label << ": no toppling in the first " << early_window << " s";
    EXPECT_NEAR(last.rotation, 0.5 * M_PI, 10.0 * kDegree) << label << ": not lying on its long face at the end";
    if (mode == "topple") {
      EXPECT_LT(std::abs(early.slip), 1e-3 * L) << label << ": the toppling block's corner slipped";
      EXPECT_LT(last.slip, 1.5 * L) << label << ": the toppled block slid on (its friction holds it)";
    } else {
      EXPECT_GT(last.slip, 3.0) << label << ": the toppled block did not slide on";
    }
  }
  std::cout << "[measured] " << label << ": first " << early_window << " s: rotation " << early.rotation << " rad, slip "
            << early.slip << " m; end: rotation " << last.rotation << " rad, slip " << last.slip << " m\n";
}

TEST_P(GoodmanBray, EachModeShowsInItsFirstMotionAndItsFinalState) {
  const auto [integrator, index] = GetParam();
  expect_mode(kModes[index], integrator, 1.0, 1.0e-3);
}

// The class: two cases of each mode (each well inside its region of the chart), blocks scaled by
// 0.2, 1 and 5 (a 0.05-5 m wide block), at 1, 5 and 10 ms (three substeps), both solvers: 144 runs, each checked
// as above (the first-motion window scaled with the block's own time). Until 2026-12-06 (model
// revision .17) the implicit solver's 5 m blocks at 1 ms toppling (topple, slide and topple: 2 of
// the 8 cases) read as gaining 27-36 J/m, 15-20 times the audit's allowance: the audit counted a
// block's kinetic energy as 1/2 m v^2 + 1/2 I w^2, and a tall block's shear strain rate turns its
// sides as a rotation would (the mass matrix couples r0 to gamma by (S_xx - S_yy) / 2), so a
// rotation rate met by an opposite shear rate was counted whole. Counted as 1/2 V^T M V
// (forward/common/energy_check.cpp) the worst is 0.8 J/m, 0.38 of the allowance.
const BlockOnIncline kModeClass[] = {
    {"stable", 20.0, 35.0, 1.0, 1.0},           {"stable", 30.0, 40.0, 1.0, 0.8},
    {"slide", 35.0, 20.0, 2.0, 1.0},            {"slide", 25.0, 15.0, 1.0, 1.5},
    {"topple", 25.0, 40.0, 0.25, 1.0},          {"topple", 30.0, 45.0, 0.4, 1.0},
    {"slide_and_topple", 35.0, 25.0, 0.25, 1.0}, {"slide_and_topple", 40.0, 30.0, 0.5, 1.0}};

class GoodmanBrayClass : public ::testing::TestWithParam<Integrator> {};

TEST_P(GoodmanBrayClass, EveryModeAtEverySizeAndStep) {
  for (const BlockOnIncline& c : kModeClass)
    for (const double scale : {0.2, 1.0, 5.0})
      for (const double step : {0.001, 0.005, 0.01}) expect_mode(c, GetParam(), scale, step, 3);
}

INSTANTIATE_TEST_SUITE_P(Toppling, GoodmanBrayClass, ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

INSTANTIATE_TEST_SUITE_P(Toppling, GoodmanBray,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Range(0, 4)),
                         [](const ::testing::TestParamInfo<ModeParam>& info) {
                           return name_of(std::get<0>(info.param)) + "_" + kModes[std::get<1>(info.param)].mode;
                         });

}  // namespace
}  // namespace ddafit
