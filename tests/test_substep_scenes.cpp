// Contact scenes where the substep solver is most likely to go wrong, run with both
// solvers: corners meeting corners, a wedge point-down on a corner, a slide over a step,
// a tall stack whose base must carry the whole weight, and a heavy block on a light one
// (1 and 2 threads: test_substep_threads.cpp).
//
// Every scene asserts physical facts, each with a named tolerance and the reason for it:
//   - energy: the kinetic energy never exceeds the initial kinetic energy plus the work
//     gravity has done (contacts and friction can only dissipate);
//   - no pass-through: a block's centroid stays outside every other block by most of its
//     inscribed radius (the blocks tip off the corner and fall past the lower block, so
//     "the centroid never below the lower block's top" would not hold; this does);
//   - penetration: the deepest overlap stays below 1 % of the smaller block's size (the
//     issue's limit): measured from the geometry at every output time for both solvers,
//     and as the substep solver reports it over every step.
#include <algorithm>
#include <vector>

#include "tests/contact_scene_audit.hpp"

namespace ddafit {
namespace {

// --- 1. Corner on corner --------------------------------------------------------------

using CornerParam = std::tuple<Integrator, int>;  // solver, rotation of the upper square in degrees

class SubstepScenesCorner : public ::testing::TestWithParam<CornerParam> {};

// Two unit squares meeting corner to corner: the lower one fixed, [0, 1] x [0, 1], the
// upper one turned by 0, 15, 45 or 90 degrees and dropped from 5 cm with its lowest
// corner 5 cm beside the lower one's top-right corner (1, 1), so that it does not balance
// exactly: at 0, 15 and 90 degrees the corner is 5 cm inside (over the top face; outside,
// a square turned 0 or 90 degrees would miss the lower one), and at 45 degrees 5 cm
// outside (inside, the square would stand balanced on its corner, its centroid straight
// above it), where its edge lands on the lower corner. 90 degrees is the 0 degree shape
// with its vertices numbered from another corner: contact features must not depend on
// the numbering. The upper square tips over the corner and falls past the lower one.
Scene corner_scene(Integrator integrator, int degrees) {
  Scene s = base_scene(1.5, 1.0e-3, 0.01, integrator);
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("lower", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), true));
  const double offset = degrees == 45 ? 0.05 : -0.05;
  const std::vector<Vec2> upper = square_with_low_corner_at(Vec2(1.0 + offset, 1.05), degrees);
  s.blocks.push_back(block("upper", upper, false));
  s.measure.push_back({"upper", centroid_of(upper)});
  return s;
}

TEST_P(SubstepScenesCorner, EnergyBoundedNoPassThrough) {
  const auto [integrator, degrees] = GetParam();
  const Scene scene = corner_scene(integrator, degrees);
  RunAudit audit;
  const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
  expect_contact_physics(r, audit, integrator, "corner " + std::to_string(degrees) + " deg, " + name_of(integrator));
}

INSTANTIATE_TEST_SUITE_P(SubstepScenes, SubstepScenesCorner,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Values(0, 15, 45, 90)),
                         [](const ::testing::TestParamInfo<CornerParam>& info) {
                           return name_of(std::get<0>(info.param)) + "_" + std::to_string(std::get<1>(info.param)) +
                                  "deg";
                         });

class SubstepScenesSolver : public ::testing::TestWithParam<Integrator> {};

// --- 2. Wedge point-down on a corner --------------------------------------------------

// A wedge (triangle 1 m across the top, 1 m deep) dropped point-down from 5 cm onto the
// lower block's top-right corner. Its point is 3 cm inside the corner, over the top face,
// and the wedge is lopsided (its top runs from 0.4 m left to 0.6 m right of the point),
// so its centroid is 6.7 cm right of the point, 3.7 cm beyond the corner: it does not
// balance, and tips over the corner onto its right flank.
TEST_P(SubstepScenesSolver, WedgeOnCorner) {
  const Integrator integrator = GetParam();
  Scene s = base_scene(1.5, 1.0e-3, 0.01, integrator);
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("lower", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), true));
  const Vec2 point(0.97, 1.05);
  const std::vector<Vec2> wedge = {point, point + Vec2(0.6, 1.0), point + Vec2(-0.4, 1.0)};
  s.blocks.push_back(block("wedge", wedge, false));
  s.measure.push_back({"wedge", centroid_of(wedge)});
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  expect_contact_physics(r, audit, integrator, "wedge, " + name_of(integrator));
}

// --- 3. A slide over a step in the incline --------------------------------------------

// A 1 m x 0.5 m block on a 2:1 incline (alpha = 26.57 deg) of friction 15 deg, so it
// accelerates at g (sin alpha - cos alpha tan phi) = 2.04 m/s^2. The incline is two fixed
// blocks whose surfaces are 5 cm apart vertically at x_step: the slider starts 0.5 m
// above the step (its front edge) and must drop over it and slide on.
TEST_P(SubstepScenesSolver, SlideOverStep) {
  const Integrator integrator = GetParam();
  Scene s = base_scene(2.0, 1.0e-3, 0.01, integrator);
  add_interface(s, "slope", 15.0);
  s.default_interface = 0;
  const Vec2 along = Vec2(2.0, -1.0).normalized();
  const Vec2 up(-along.y(), along.x());
  const double upper_length = 3.0, lower_length = 8.0, drop = 0.05;
  const Vec2 edge = upper_length * along;  // top of the step
  const Vec2 foot = edge - Vec2(0.0, drop);  // bottom of the step
  const Vec2 down(0.0, -1.0);
  s.blocks.push_back(block("upper_plane", {Vec2::Zero(), edge, edge + 1.5 * down, 1.5 * down}, true));
  const Vec2 far = foot + lower_length * along;
  s.blocks.push_back(block("lower_plane", {foot, far, far + down, foot + down}, true));
  const double length = 1.0, height = 0.5;
  const Vec2 origin = (upper_length - 0.5 - length) * along;  // rear bottom corner
  s.blocks.push_back(block("slider", box(origin, along, up, length, height), false));
  s.measure.push_back({"centre", origin + 0.5 * length * along + 0.5 * height * up});
  s.measure.push_back({"rear", origin + 0.02 * along + 0.02 * up});  // just inside the rear bottom corner
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  const std::string label = "step, " + name_of(integrator);
  expect_contact_physics(r, audit, integrator, label);
  ASSERT_FALSE(r.history.empty());

  // Passed the step: the rear of the block is beyond it at the end.
  double rear_final_x = -1e300, speed_final = 0.0, speed_at_pass = -1.0, time_at_pass = -1.0, time_final = 0.0;
  for (const HistoryRow& row : r.history) {
    if (row.point == 1) {
      rear_final_x = row.position.x();
      if (time_at_pass < 0.0 && row.position.x() > edge.x()) time_at_pass = row.time;
    } else {
      speed_final = row.velocity.dot(along);
      time_final = row.time;
      if (time_at_pass >= 0.0 && speed_at_pass < 0.0) speed_at_pass = row.velocity.dot(along);
    }
  }
  EXPECT_GT(rear_final_x, edge.x()) << label << ": the slider did not pass the step at x = " << edge.x();
  // Keeps going: on the lower plane (tan alpha > tan phi) it must accelerate again, so it
  // ends faster than it was when its rear passed the step.
  EXPECT_GT(speed_final, speed_at_pass) << label;
  std::cout << "[measured] " << label << ": step at x = " << edge.x() << ", rear at " << rear_final_x
            << " at the end; rear passed the step at t = " << time_at_pass << " s at " << speed_at_pass
            << " m/s, final speed " << speed_final << " m/s at t = " << time_final
            << " s (no-step analytic: " << 2.04 * time_final << " m/s)\n";
}

// --- 4. A tall column sliding as one --------------------------------------------------

// A column of ten 1 m tall slabs sliding down a 2:1 incline (alpha = 26.57 deg), friction
// 20 deg on its base and 40 deg between the slabs, so it slides as one body (the joints
// need tan phi = 0.36 of their normal force to move with the base, and have 0.84). Its
// acceleration a = g (sin alpha - cos alpha tan phi) = 1.19 m/s^2 only holds if the base
// carries the column's whole weight component m g cos alpha: a base under-loaded by 1 %
// (a compliant stack still sinking into its contacts) loses 1 % of its friction and
// slides 2.7 % faster (d a = g cos alpha tan phi x 1 % = 0.032 m/s^2). The slabs are
// 6 m wide, not 1 m: a
// 1 m x 10 m column topples (its centroid lies 2.2 m downslope of its base centre at
// rest), and while sliding the base friction moves the resultant tan(phi) x 5 m = 1.8 m
// downslope of the centre, inside a 6 m base with a 1.2 m margin.
TEST_P(SubstepScenesSolver, ColumnSlidesAsOne) {
  const Integrator integrator = GetParam();
  // 1 % of the analytic acceleration, as the issue asks: stricter than 1 % of the base
  // load, which would show as 2.7 % of the acceleration (above); the implicit solver
  // keeps the incline verification case to far less than that.
  constexpr double kAccelerationTolerance = 0.01;
  constexpr double kFitStart = 0.3, kFitEnd = 1.5;  // s: after the start-up transient
  constexpr double kBaseFriction = 20.0, kJointFriction = 40.0, kWidth = 6.0;
  Scene s = base_scene(kFitEnd, 1.0e-3, 0.01, integrator);
  const int base = add_interface(s, "base", kBaseFriction);
  const int joint = add_interface(s, "joint", kJointFriction);
  s.contact_rules.push_back({"plane", "column", base});
  s.contact_rules.push_back({"column", "column", joint});
  const double run = 30.0, drop = 15.0;
  s.blocks.push_back(block("plane", {{0, 0}, {run, -drop}, {run, -drop - 2}, {0, -2}}, true, 0, "plane"));
  const Vec2 along = Vec2(run, -drop).normalized();
  const Vec2 up(-along.y(), along.x());
  const Vec2 origin = 2.0 * along;
  for (int k = 0; k < 10; ++k)
    s.blocks.push_back(block("slab_" + std::to_string(k), box(origin + k * up, along, up, kWidth, 1.0), false, 0, "column"));
  s.measure.push_back({"base", origin + 0.5 * kWidth * along + 0.5 * up});  // centre of the bottom slab
  s.measure.push_back({"top", origin + 0.5 * kWidth * along + 9.5 * up});   // centre of the top slab

  const SimulationResult r = simulate(s);
  const std::string label = "column, " + name_of(integrator);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;

  // Least squares s(t) = c0 + c1 t + a t^2 / 2 over the window: the linear term takes up
  // whatever velocity the start-up transient left, the curvature is the acceleration.
  const auto fitted_acceleration = [&](int point) {
    std::vector<double> ts, ss;
    for (const HistoryRow& row : r.history)
      if (row.point == point && row.time >= kFitStart - 1e-9 && row.time <= kFitEnd + 1e-9) {
        ts.push_back(row.time);
        ss.push_back(row.displacement.dot(along));
      }
    EXPECT_GE(ts.size(), 50u) << label;
    Eigen::MatrixXd A(ts.size(), 3);
    Eigen::VectorXd b(ts.size());
    for (size_t i = 0; i < ts.size(); ++i) {
      A(i, 0) = 1.0;
      A(i, 1) = ts[i];
      A(i, 2) = 0.5 * ts[i] * ts[i];
      b(i) = ss[i];
    }
    return Eigen::Vector3d(A.colPivHouseholderQr().solve(b));
  };
  const double alpha = std::atan(drop / run);
  const double analytic = std::abs(s.gravity.y()) * (std::sin(alpha) - std::cos(alpha) * std::tan(kBaseFriction * kDegree));
  const Eigen::Vector3d base_fit = fitted_acceleration(0), top_fit = fitted_acceleration(1);
  const double error = (base_fit(2) - analytic) / analytic;
  EXPECT_LT(std::abs(error), kAccelerationTolerance)
      << label << ": fitted acceleration " << base_fit(2) << " m/s^2, analytic " << analytic << " m/s^2";
  // Slides as one: the top slab, 9 m up the column, accelerates with the base (a column
  // rocking, toppling or shearing at its 40 deg joints would not), to the same tolerance.
  const double top_error = (top_fit(2) - analytic) / analytic;
  EXPECT_LT(std::abs(top_error), kAccelerationTolerance)
      << label << ": top slab's fitted acceleration " << top_fit(2) << " m/s^2, analytic " << analytic << " m/s^2";
  std::cout << "[measured] " << label << ": base acceleration " << base_fit(2) << " m/s^2 vs analytic " << analytic
            << " (error " << 100.0 * error << " %), top " << top_fit(2) << " (error " << 100.0 * top_error
            << " %), fitted start velocity " << base_fit(1) << " m/s, solver penetration "
            << r.summary.solver.worst_penetration_ratio << ", steps " << r.summary.run.steps << "\n";
}

// --- 5. A heavy block on a light one --------------------------------------------------

// A 1 m block 100 times as dense as rock on a 1 m block of a tenth of rock's density
// (mass ratio 100), on a fixed floor, all joints 30 deg. Nothing drives them: they must
// stay put. Elastic shortening under the heavy block's 265 kPa is 53 um over the light
// block's height (5 GPa) and the contacts compress by less, so 1 mm is twenty times the
// settling and still small against any real slip or sinking; the substep solver's
// Gauss-Seidel sweeps converge slowest at such a mass ratio, and a light block squeezed
// out or a heavy one sinking into it shows as millimetres within a second.
TEST_P(SubstepScenesSolver, HeavyOnLightStaysPut) {
  const Integrator integrator = GetParam();
  constexpr double kMaxMovement = 1e-3;  // m
  Scene s = base_scene(2.0, 1.0e-3, 0.01, integrator);
  s.materials[0].density = 0.1 * kRockDensity;  // light
  s.materials.push_back({"heavy", 10.0 * kRockDensity, 5.0e9, 0.25});
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("floor", box({-2, -1}, {1, 0}, {0, 1}, 5.0, 1.0), true));
  s.blocks.push_back(block("light", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), false, 0));
  s.blocks.push_back(block("heavy", box({0, 1}, {1, 0}, {0, 1}, 1.0, 1.0), false, 1));
  s.measure.push_back({"light", {0.5, 0.5}});
  s.measure.push_back({"heavy", {0.5, 1.5}});
  const SimulationResult r = simulate(s);
  const std::string label = "heavy on light, " + name_of(integrator);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  ASSERT_EQ(r.summary.points.size(), 2u);
  for (const PointSummary& p : r.summary.points)
    EXPECT_LT(p.max_total_displacement, kMaxMovement) << label << ": block '" << p.name << "' moved";
  std::cout << "[measured] " << label << ": light moved " << r.summary.points[0].max_total_displacement
            << " m, heavy moved " << r.summary.points[1].max_total_displacement << " m, solver penetration "
            << r.summary.solver.worst_penetration_ratio << " groups " << r.summary.solver.impact_groups << " large " << r.summary.solver.impact_groups_too_large << " refused " << r.summary.solver.impact_groups_refused << "\n";
}

// The class of the scene above: a 1 x 0.5 m block 30, 100, 450 and 1000 times as heavy as each
// of the `cubes` cubes under it (five of 0.2 m, ten of 0.1 m), on a floor at 0, 10 and 20 deg
// (every joint at 30 deg friction), at the default 1 ms x 4, at 5 ms x 4 and at Vajont's
// 10 ms x 3, for 1 s; the heavy block starts `drop` m above the cubes. Returns the largest move
// of a cube (36 runs), its run, and each run's largest cube move.
struct HeavyOnCubes {
  double worst = 0.0;
  std::string label;
  std::vector<double> moves;
  int over(double bound) const { return static_cast<int>(std::count_if(moves.begin(), moves.end(), [&](double x) { return x >= bound; })); }
};
HeavyOnCubes heavy_blocks_on_cubes(Integrator integrator, double drop, int cubes = 5) {
  constexpr double kMaxOverlap = kOverlapBoundRatio;  // 1 % of the smaller block (run_record.hpp)
  constexpr double kLength = 1.0, kHeight = 0.5;
  const double kCube = kLength / cubes;
  HeavyOnCubes result;
  int runs = 0;
  for (const double ratio : {30.0, 100.0, 450.0, 1000.0})
    for (const double slope : {0.0, 10.0, 20.0})
      for (const auto& [step, substeps] : {std::pair{1e-3, 4}, std::pair{5e-3, 4}, std::pair{1e-2, 3}}) {
        Scene s = base_scene(1.0, step, 0.01, integrator);
        s.options.substeps = substeps;
        const double density = ratio * kCube * kCube / (kLength * kHeight) * kRockDensity;
        s.materials.push_back({"heavy", density, 5.0e9, 0.25});
        add_interface(s, "joint", 30.0);
        s.default_interface = 0;
        const double a = slope * kDegree;
        const Vec2 along(std::cos(a), std::sin(a)), up(-std::sin(a), std::cos(a));
        s.blocks.push_back(block("floor", box(-1.0 * along - up, along, up, 3.0, 1.0), true));
        for (int i = 0; i < cubes; ++i) {
          const std::string name = "cube" + std::to_string(i);
          s.blocks.push_back(block(name, box(i * kCube * along, along, up, kCube, kCube), false));
          s.measure.push_back({name, i * kCube * along + 0.5 * kCube * (along + up)});
        }
        s.blocks.push_back(block("heavy", box((kCube + drop) * up, along, up, kLength, kHeight), false, 1));
        const SimulationResult r = simulate(s);
        char label[200];
        std::snprintf(label, sizeof label, "%s: heavy %g times each of %d cubes, dropped %g m, slope %g deg, %g ms x %d",
                      name_of(integrator).c_str(), ratio, cubes, drop, slope, step * 1e3, substeps);
        ++runs;
        EXPECT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
        double largest = 0.0;
        for (const PointSummary& p : r.summary.points) largest = std::max(largest, p.max_total_displacement);
        result.moves.push_back(largest);
        if (largest > result.worst) result.worst = largest, result.label = label;
        EXPECT_LT(r.summary.solver.worst_penetration_ratio, kMaxOverlap) << label;
      }
  EXPECT_EQ(runs, 36);
  return result;
}

// At rest, substep solver: no cube may move more than 1 mm (kMaxMovement of the test above; a
// heavy block sinking into or shoving the cubes shows as millimetres within a second). Measured
// 2026-12-05 (revision .12.05.2): 0.22 mm worst (1000 times a cube, flat, 5 ms x 4); 0.31 mm
// without the extra sweeps of converge_heavy.hpp: warm-started, the two sweeps hold a resting load.
TEST(SubstepScenesHeavy, HeavyBlocksRestOnRowsOfLightCubesAtAnyStepAndSlopeSubstep) {
  constexpr double kMaxMovement = 1e-3;  // m
  const HeavyOnCubes h = heavy_blocks_on_cubes(Integrator::Substep, 0.0);
  EXPECT_LT(h.worst, kMaxMovement) << h.label;
  std::cout << "[measured] heavy blocks resting on rows of light cubes: largest cube move " << h.worst << " m ("
            << h.label << ")\n";
}

// Dropped 0.05 and 0.2 m (landing at 1 and 2 m/s; on the slopes its direction is 10-20 deg off
// the floor's normal, inside the 30 deg friction cone, so a rigid stack stops without slipping),
// on five 0.2 m and ten 0.1 m cubes: no cube may move more than 5 % of its size. The implicit
// solver, dropped 0.2 m: 4.2 mm worst on five cubes (1000 times a cube, 20 deg, 1 ms), measured
// 2026-12-05.
constexpr double kLandingShareOfCube = 0.05;
TEST(SubstepScenesHeavy, HeavyBlocksLandOnRowsOfLightCubesImplicit) {
  for (const int cubes : {5, 10}) {
    const HeavyOnCubes h = heavy_blocks_on_cubes(Integrator::Implicit, 0.2, cubes);
    EXPECT_LT(h.worst, kLandingShareOfCube / cubes) << h.label;
    std::cout << "[measured] heavy blocks landing on rows of light cubes: largest cube move " << h.worst << " m ("
              << h.label << ")\n";
  }
}

// Substep solver. Found 2026-12-05 by this sweep (five cubes, 0.2 m): at revision .12.05.2 cubes
// moved up to 0.53 m (100 times a cube, 20 deg, 1 ms x 4). The heavy block, landing at 1.99 m/s,
// left at 1.37 m/s upwards: the impact group of the landing's first substep set it settling, the
// group of the next stopped it, and as a settling block it was not marked struck, so the next
// warm start handed on the whole impulse that had stopped it (mended at .12.05.3: struck_again,
// converge_impacts.cpp; 16 of 36 runs still over 1 cm, worst 0.14 m). What was left was the
// landing's friction: the heavy block slid on down the slope at the tangential speed it landed
// with (0.6 m/s at 1000 times, 20 deg), the group's one sweep handing it a thousandth of the
// cubes' friction; since .12.05.4 a group with a heavy block beside a light one solves its
// friction with its normals (solve_group_friction.hpp). Measured 2026-12-05 at .12.05.4, five
// cubes: 7.5 mm worst (dropped 0.2 m, 30 times, 10 deg, 1 ms x 4) and 1.4 mm (0.05 m), none of
// the 72 runs over 1 cm.
void expect_landings_within(int cubes) {
  for (const double drop : {0.05, 0.2}) {
    const HeavyOnCubes h = heavy_blocks_on_cubes(Integrator::Substep, drop, cubes);
    const double bound = kLandingShareOfCube / cubes;
    EXPECT_LT(h.worst, bound) << h.label;
    std::cout << "[measured] heavy blocks landing on rows of light cubes: largest cube move " << h.worst << " m ("
              << h.label << "), " << h.over(bound) << " of 36 runs at or over " << bound << " m\n";
  }
}
TEST(SubstepScenesHeavy, HeavyBlocksLandOnRowsOfLightCubesSubstep) { expect_landings_within(5); }

// On ten 0.1 m cubes (bound 5 mm). Found 2026-12-05 at .12.05.4: 1 of 72 runs over (450 times a
// cube, dropped 0.05 m, 20 deg, 10 ms x 3): the group's one sweep after its friction solve set
// the downslope end cube sliding out from under the block at 0.25 m/s, 7.3 mm; mended at
// .12.05.5, which skips that sweep (solve_impact_group.cpp).
TEST(SubstepScenesHeavy, HeavyBlocksLandOnRowsOfTenLightCubesSubstep) { expect_landings_within(10); }

INSTANTIATE_TEST_SUITE_P(SubstepScenes, SubstepScenesSolver,
                         ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

}  // namespace
}  // namespace ddafit
