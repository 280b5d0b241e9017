// Blocks of landslide size sliding from rest: seed Eq. 4 (the incline check of seed §2.3, Fig. 6)
// for the blocks a back-analysis runs, not only the seed's 2.23 m block. The class: sliders of
// 10 x 2.5, 30 x 8, 90 x 24 and 200 x 50 m, on faces of 40, 35 and 28 deg at friction 25, 33 and
// 18 deg (the 35/33 face accelerates at 0.41 m/s^2, where a start's error shows most), on one
// fixed block or across joints every third of the slider, at time steps of 0.05, 0.2 and 0.7 of
// the slider's elastic period L/c (L = sqrt(area), c = sqrt(E/rho)): 72 runs a solver, with the
// run's default step control. Tolerance: test_joint_crossing.cpp's 1 % of Eq. 4 wherever the
// slider has moved 1 cm, and the strict run audit (contact_scene_audit.hpp).
//
// Until model revision 2026-12-06.3 the implicit solver failed 10 of these 72 runs on "contacts
// are creating energy" (every 200 m slider at 0.05 and 0.2 L/c; 90 m at 40/25 deg at 0.05) and
// ran others up to 105 % off Eq. 4 at the first centimetre (90 m at 35/33 deg, 0.05 L/c; 30 m:
// 40 %, 10 m: 12 % at 0.1 L/c). Its settling before t = 0 held every point locked, and a block
// that then slid started with the normal forces and strain of one held by its shear springs
// (forward/step/settle_sliding.hpp). Measured after it (2026-12-06): worst 3.7e-3, at 0.05 L/c.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <tuple>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

struct SliderSize {
  double length, height;  // m
};

using LandslideParam = std::tuple<Integrator, int>;
class LandslideBlocks : public ::testing::TestWithParam<LandslideParam> {};

constexpr SliderSize kSizes[] = {{10.0, 2.5}, {30.0, 8.0}, {90.0, 24.0}, {200.0, 50.0}};

TEST_P(LandslideBlocks, SlideFromRestAsSeedEq4SaysAtEveryStepOverTheirElasticPeriod) {
  const auto [integrator, size_index] = GetParam();
  const SliderSize size = kSizes[size_index];
  const double slopes[][2] = {{40, 25}, {35, 33}, {28, 18}};
  double worst = 0.0;
  std::string worst_label;
  for (const auto& slope : slopes)
    for (const bool jointed : {false, true})
      for (const double share : {0.05, 0.2, 0.7}) {
        Crossing c;
        c.slope = slope[0], c.friction = slope[1];
        c.length = size.length, c.height = size.height;
        c.spacing = jointed ? size.length / 3.0 : 1e4;  // one fixed block under the whole path
        c.front_gap = jointed ? 0.37 * c.spacing : 0.5 * c.spacing;  // unjointed: mid-block, no joint on the way
        Scene scene = crossing_scene(c, integrator);
        scene.max_step = share * elastic_period(c);
        scene.output_interval = scene.max_step;  // each step an output: no step shortened to land on one
        RunAudit audit;
        const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
        const std::string label = describe(c, integrator) + (jointed ? "" : " (one base block)") + ", step " +
                                  std::to_string(share) + " L/c";
        expect_contact_physics(r, audit, integrator, label);
        double when = 0.0;
        const double error = displacement_error(r, c, &when);
        EXPECT_LT(error, kDisplacementTolerance) << label << ": worst at t = " << when << " s";
        if (error > worst) worst = error, worst_label = label;
      }
  std::cout << "[measured] " << name_of(integrator) << ", sliders " << size.length << " x " << size.height
            << " m: worst " << worst << " of seed Eq. 4 (" << worst_label << ")\n";
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, LandslideBlocks,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Range(0, 4)),
                         [](const ::testing::TestParamInfo<LandslideParam>& info) {
                           const SliderSize s = kSizes[std::get<1>(info.param)];
                           return name_of(std::get<0>(info.param)) + "_" + std::to_string(static_cast<int>(s.length)) +
                                  "m";
                         });

// The same slide without friction: a 200 x 50 m block on a 35 deg face. Until revision
// 2026-12-06.3 the implicit solver stopped at its 9th step ("contacts are creating energy"):
// released from the locked settling, the block's normal forces (shared 1.27 : 0.90 between its
// corners to balance the moment of the shear that held it) set it rocking and shearing on its
// springs. Frictionless, seed Eq. 4 is g sin(alpha) t^2 / 2 to round-off (measured 3.4e-9).
TEST(LandslideBlocks, AFrictionlessSlabSlidesAsSeedEq4SaysImplicit) {
  Crossing c;
  c.slope = 35.0, c.friction = 0.0, c.length = 200.0, c.height = 50.0, c.spacing = 1e4, c.front_gap = 5e3;
  const Scene scene = crossing_scene(c, Integrator::Implicit);
  RunAudit audit;
  const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
  expect_contact_physics(r, audit, Integrator::Implicit, describe(c, Integrator::Implicit));
  double when = 0.0;
  EXPECT_LT(displacement_error(r, c, &when), 1e-6) << "worst at t = " << when << " s";
}

// Two such blocks stacked, the upper one (0.8 of the lower's length) resting on the lower, the
// pair sliding from rest on one fixed face: they slide together (their joint is steeper held than
// the face, friction alike), both as seed Eq. 4 says. Measured with `ddafit simulate` before
// revision 2026-12-06.3, 1 ms steps: 100 x 25 m blocks on 35 deg at 30 deg stopped at t = 0.01 s on
// "contacts are creating energy"; 20 x 5 m blocks ran 22 % off at the first centimetre (the upper
// one). After: within 1.2e-5, on a plane 4 blocks long and on one 100 times the blocks' length (10 km),
// where settle_contacts stops before any shear spring passes its cap (2.5 mm of move per pass) and
// until revision 2026-12-06.5 the upper block still ran 22 % off (settle_sliding.cpp, overloaded groups).
TEST(LandslideBlocks, AStackOfTwoSlidesAsOneAsSeedEq4SaysImplicit) {
  for (const double length : {20.0, 100.0})
    for (const auto& [slope, friction] : {std::pair{35.0, 30.0}, std::pair{40.0, 25.0}})
      for (const double plane : {4.0, 100.0}) {  // the plane's length in blocks, no joint on the way
        Crossing c;
        c.slope = slope, c.friction = friction, c.length = length, c.height = 0.25 * length;
        c.spacing = plane * length, c.front_gap = 0.5 * plane * length;
        Scene scene = crossing_scene(c, Integrator::Implicit);
        const Slope face(slope);
        const Vec2 rear = scene.blocks.back().polygon[0];  // the lower block's rear corner on the face
        BlockInput upper = block("upper", box(rear + 0.1 * length * face.along + c.height * face.up, face.along,
                                              face.up, 0.8 * length, c.height), false);
        scene.blocks.push_back(upper);
        scene.measure.push_back({"upper", rear + 0.5 * length * face.along + 1.5 * c.height * face.up});
        RunAudit audit;
        const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
        const std::string label = describe(c, Integrator::Implicit) + ", a second block on it, plane " +
                                  std::to_string(static_cast<int>(plane)) + " blocks long";
        expect_contact_physics(r, audit, Integrator::Implicit, label);
        // Both measure points (the lower block's centre, then the upper's) against Eq. 4.
        const double a = eq4_acceleration(slope, friction);
        const double worst = slide_error(r, face, [a](const std::vector<double>& times) {
                               std::vector<double> exact;
                               for (const double t : times) exact.push_back(0.5 * a * t * t);
                               return exact;
                             }).worst;
        EXPECT_LT(worst, kDisplacementTolerance) << label;
        std::cout << "[measured] " << label << ": worst " << worst << " of seed Eq. 4\n";
      }
}

// Short steps: the class of the first test (sizes, faces, one base block or joints) at 0.001 and
// 0.005 of each slider's elastic period L/c, implicit solver, 0.6 s (every slider has moved 1 cm by
// then; an output every 0.01 s, a whole number of steps apart). Until model revision 2026-12-06.6
// these ran up to 78 % off seed Eq. 4 (a 200 x 50 m slider on 35 deg at 33 deg at 0.005 L/c; a
// 90 x 24 m one 53 % at 0.003 L/c), and `ddafit simulate` warned below 0.01 L/c. Two causes:
//   - a point's spring was unloaded at its start-of-step gap plus max_pushout_speed x dt, so a
//     resting point could hold no more than the penalty times 1 m/s x dt: the 200 m slider's
//     resting overlap, 0.5 mm, exceeds 0.37 mm at 0.005 L/c, and the block sank and rocked
//     (forward/step/assemble.hpp, spring_reference, now holds the overlap its load held);
//   - the settling passes took 30 run steps, 0.15 L/c, where inertia outweighs the springs: a pass
//     closed 3.5 % of the way to rest, which read as a block falling, and the slider started
//     unloaded (forward/step/settle_contacts.hpp, kSettlePeriods: now at least one L/c).
// Measured after it with scripts/landslide_block_steps.py (the same class, 1.5 s, an output every
// step): worst 4.7e-6 at 0.005 L/c, 8.7e-4 at 0.001, 1.1e-3 at 0.0003. Tolerance: 1 % (the class's).
TEST(LandslideBlocks, SlideFromRestAsSeedEq4SaysAtShortStepsImplicit) {
  const double slopes[][2] = {{40, 25}, {35, 33}, {28, 18}};
  for (const SliderSize& size : kSizes)
    for (const double share : {0.001, 0.005}) {
      double worst = 0.0;
      for (const auto& slope : slopes)
        for (const bool jointed : {false, true}) {
          Crossing c;
          c.slope = slope[0], c.friction = slope[1];
          c.length = size.length, c.height = size.height;
          // Unjointed: one base block 4 L + 10 m long, the slider at its middle (the plane 10 km
          // long of the first test: the last test below).
          c.spacing = jointed ? size.length / 3.0 : 4.0 * size.length + 10.0;
          c.front_gap = jointed ? 0.37 * c.spacing : 0.5 * c.spacing;
          Scene scene = crossing_scene(c, Integrator::Implicit);
          scene.duration = 0.6;
          set_step_share(scene, c, share);
          const SimulationResult r = simulate(scene);
          const std::string label = describe(c, Integrator::Implicit) + ", step " + std::to_string(share) + " L/c";
          ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
          double when = 0.0;
          const double error = displacement_error(r, c, &when);
          EXPECT_LT(error, kDisplacementTolerance) << label << ": worst at t = " << when << " s";
          worst = std::max(worst, error);
        }
      std::cout << "[measured] sliders " << size.length << " x " << size.height << " m at " << share
                << " L/c: worst " << worst << " of seed Eq. 4\n";
    }
}

// The short-step warning (forward/simulation.cpp) comes below 3e-4 L/c of the largest free block,
// the shortest step checked above: a 200 x 50 m slider (L/c = 73 ms) is warned at 2e-4 L/c and not
// at 4e-4 L/c. (A contract of the warning's place; 5 ms of run is enough to read it.)
TEST(LandslideBlocks, StepsShorterThanTheCheckedOnesAreWarnedAbout) {
  Crossing c;
  c.slope = 35.0, c.friction = 33.0, c.length = 200.0, c.height = 50.0, c.spacing = 1e4, c.front_gap = 5e3;
  for (const double share : {2e-4, 4e-4}) {
    Scene scene = crossing_scene(c, Integrator::Implicit);
    scene.duration = 0.005;
    scene.max_step = share * elastic_period(c);
    scene.output_interval = 0.0;
    const SimulationResult r = simulate(scene);
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << r.summary.message;
    bool warned = false;
    for (const std::string& w : r.summary.warnings) warned = warned || w.find("time.step") != std::string::npos;
    EXPECT_EQ(warned, share < 3e-4) << share << " L/c";
  }
}

// Sliders on a plane hundreds to thousands of times their size, at steps far shorter than their
// elastic period: 3 x 0.75, 10 x 2.5 and 30 x 8 m sliders on the first test's 10 km base block,
// 35 deg at 33 deg and 28 deg at 18 deg, at 0.001 L/c. Until model revision 2026-12-06.7 those on
// 35/33 deg ran 5.7 %, 17 % and 106 % off seed Eq. 4 (they started exact): the contact tolerance
// was 1e-7 of the largest move allowed per step, 0.005 of the half model, so 2.5 um here, as deep
// as the 10 m slider's whole resting overlap (2.6 um); a point that opened while the block rocked
// closed only that deep, and the block chattered. The tolerance is now at most a tenth of the
// heaviest free block's resting overlap (forward/step/control_time_step.hpp,
// kRestingOverlapShare): measured worst 2.9e-4. Tolerance: the class's 1 %.
TEST(LandslideBlocks, SlidersOnAPlaneAThousandTimesTheirLengthAtAThousandthOfTheirPeriodImplicit) {
  const SliderSize sizes[] = {{3.0, 0.75}, {10.0, 2.5}, {30.0, 8.0}};
  const double slopes[][2] = {{35, 33}, {28, 18}};
  double worst = 0.0;
  for (const SliderSize& size : sizes)
    for (const auto& slope : slopes) {
      Crossing c;
      c.slope = slope[0], c.friction = slope[1], c.length = size.length, c.height = size.height;
      c.spacing = 1e4, c.front_gap = 5e3;
      Scene scene = crossing_scene(c, Integrator::Implicit);
      scene.duration = 0.6;
      set_step_share(scene, c, 0.001);
      const SimulationResult r = simulate(scene);
      const std::string label = describe(c, Integrator::Implicit);
      ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
      double when = 0.0;
      const double error = displacement_error(r, c, &when);
      EXPECT_LT(error, kDisplacementTolerance) << label << ": worst at t = " << when << " s";
      worst = std::max(worst, error);
    }
  std::cout << "[measured] sliders on a 10 km plane at 0.001 L/c: worst " << worst << " of seed Eq. 4\n";
}

// Two blocks stacked on a face, the joint between them weaker than the face (bedding weaker than
// the slide's base): the upper block slides off the lower one at g (sin a - cos a tan phi_j),
// and the lower one, dragged by it at tan phi_j of its weight, slides at
// g sin a - g cos a (2 tan phi_b - tan phi_j) if that is positive (equal masses), else stays.
struct WeakJointFace {
  double slope, basal, joint;  // deg: the face's dip, its friction angle, the joint's
};

// How far the lower block is from sliding: 1 - (its drive along the face) / (the face's capacity),
// sin a + cos a tan phi_j against 2 cos a tan phi_b; negative where it slides.
double holding_margin(const WeakJointFace& f) {
  const double sine = std::sin(f.slope * kDegree), cosine = std::cos(f.slope * kDegree);
  return 1.0 - (sine + cosine * std::tan(f.joint * kDegree)) / (2.0 * cosine * std::tan(f.basal * kDegree));
}

struct WeakJointClass {
  std::vector<double> lengths;  // m, each block; height a quarter of it
  std::vector<WeakJointFace> faces;
  std::vector<double> shares;  // the step, as a share of the block's L/c
};

// The first class (2026-12-06): 20 and 100 m; 35/30/20 (the lower block held, margin 7.8 %),
// 40/30/25 (both slide), 35/33/28 (held, 5.2 %); 0.05 and 0.3 L/c.
const WeakJointClass kFirstWeakJointClass = {{20.0, 100.0}, {{35, 30, 20}, {40, 30, 25}, {35, 33, 28}}, {0.05, 0.3}};
// A wider one (revision 2026-12-06.9): 5-200 m; 30/28/20 (held, 11.5 %), 45/40/30 (held, 6.0 %),
// 38/30/29 (both slide), 33/31/25 (held, 7.2 %), 50/45/40 (both slide), 25/22/10 (held, 20 %);
// 0.02, 0.1 and 0.5 L/c.
const WeakJointClass kWideWeakJointClass = {{5.0, 20.0, 50.0, 200.0},
                                            {{30, 28, 20}, {45, 40, 30}, {38, 30, 29}, {33, 31, 25}, {50, 45, 40},
                                             {25, 22, 10}},
                                            {0.02, 0.1, 0.5}};

// The stacks of `cls` whose face `take` accepts, 1.5 s each, against the closed form: the lower
// block held within 1 mm; a sliding block within 1 % once it has moved 1 cm.
void expect_weak_joint_stack(Integrator integrator, const WeakJointClass& cls,
                             const std::function<bool(const WeakJointFace&)>& take) {
  double worst = 0.0;
  int failed = 0, runs = 0;
  for (const double length : cls.lengths)
    for (const WeakJointFace& f : cls.faces)
      for (const double share : cls.shares) {
        if (!take(f)) continue;
        ++runs;
        Crossing c;
        c.slope = f.slope, c.friction = f.basal, c.length = length, c.height = 0.25 * length;
        c.spacing = 4.0 * length, c.front_gap = 2.0 * length;  // one base block, no joint on the way
        Scene scene = crossing_scene(c, integrator);
        set_step_share(scene, c, share);
        Interface weak = scene.interfaces[0];
        weak.name = "joint";
        weak.friction_angle = f.joint;
        scene.interfaces.push_back(weak);
        scene.contact_rules.push_back({"slider", "upper", 1});
        const Slope face(f.slope);
        const Vec2 rear = scene.blocks.back().polygon[0];  // the lower block's rear corner on the face
        scene.blocks.push_back(
            block("upper", box(rear + c.height * face.up, face.along, face.up, c.length, c.height), false));
        scene.measure.push_back({"upper", rear + 0.5 * length * face.along + 1.5 * c.height * face.up});
        const SimulationResult r = simulate(scene);
        const std::string label = describe(c, integrator) + ", joint " + std::to_string(f.joint) + " deg, step " +
                                  std::to_string(share) + " L/c";
        // auto: two free blocks and none of the known limits' classes, so the implicit solver (from
        // model revision 2026-12-06.8 to .13 such stacks went to the substep solver, Known limits (l)).
        if (integrator == Integrator::Auto) {
          EXPECT_EQ(r.summary.solver.integrator, Integrator::Implicit) << label << ": " << r.summary.solver.reason;
        }
        if (r.summary.status != RunStatus::Completed) {
          ADD_FAILURE() << label << ": " << r.summary.message;
          ++failed;
          continue;
        }
        const double g = 9.81, sine = std::sin(f.slope * kDegree), cosine = std::cos(f.slope * kDegree);
        const double mu_b = std::tan(f.basal * kDegree), mu_j = std::tan(f.joint * kDegree);
        const double upper_a = g * (sine - cosine * mu_j);
        const double lower_a = std::max(0.0, g * sine - g * cosine * (2.0 * mu_b - mu_j));
        double error = 0.0;
        for (const HistoryRow& row : r.history) {
          const double a = row.point == 0 ? lower_a : upper_a;
          const double exact = 0.5 * a * row.time * row.time, moved = row.displacement.dot(face.along);
          if (a == 0.0) {
            if (std::abs(moved) > 1e-3) error = std::max(error, 1.0);
          } else if (exact >= 0.01) {
            error = std::max(error, std::abs(moved - exact) / exact);
          }
        }
        EXPECT_LT(error, kDisplacementTolerance) << label;
        worst = std::max(worst, error);
      }
  std::cout << "[measured] " << name_of(integrator) << ", " << runs << " stacks with a weaker joint: worst " << worst
            << " of the closed form, " << failed << " stopped\n";
}

constexpr auto kEveryFace = [](const WeakJointFace&) { return true; };

// A lower block held by less than this share of its face's capacity crept on the implicit solver
// until model revision 2026-12-06.14 (Known limits (l)).
constexpr double kNarrowHold = 0.07;
bool held_narrowly(const WeakJointFace& f) {
  const double margin = holding_margin(f);
  return margin > 0.0 && margin < kNarrowHold;
}

// time.integrator: auto sent these small scenes (two free blocks) to the substep solver from model
// revision 2026-12-06.8 to .13, while the implicit solver let a narrowly held lower block creep;
// since .14 it holds them (below), and auto runs them on it.
TEST(LandslideBlocks, AutoRunsAStackWithAWeakerJointOnTheImplicitSolver) {
  expect_weak_joint_stack(Integrator::Auto, kFirstWeakJointClass, kEveryFace);
}

// The substep solver: worst 7.6e-6 on the first class, 5.8e-3 on the wide one (measured
// 2026-12-06 through `ddafit simulate` and this test).
TEST(LandslideBlocks, AStackWithAWeakerJointSlidesApartAsTheClosedFormSaysSubstep) {
  expect_weak_joint_stack(Integrator::Substep, kFirstWeakJointClass, kEveryFace);
  expect_weak_joint_stack(Integrator::Substep, kWideWeakJointClass, kEveryFace);
}

// The implicit solver. Until model revision 2026-12-06.9 it ran 8 of the first class's 12 over
// their bound and stopped a ninth: its settling before t = 0 (forward/step/settle_sliding.cpp)
// ran the two blocks as one sliding group with one acceleration, where the joint slips and they
// accelerate apart. Each block now takes its own, and a lower block whose net force points
// against its slip is held. Every stack but those held narrowly (below) is within its bound
// (worst measured 7.8e-3, 200 m at 50/45/40 deg, 0.02 L/c, where the lower block's acceleration is
// 0.02 g; 2026-12-06).
TEST(LandslideBlocks, AStackWithAWeakerJointSlidesApartAsTheClosedFormSaysImplicit) {
  const auto broad = [](const WeakJointFace& f) { return !held_narrowly(f); };
  expect_weak_joint_stack(Integrator::Implicit, kFirstWeakJointClass, broad);
  expect_weak_joint_stack(Integrator::Implicit, kWideWeakJointClass, broad);
}

// A lower block held by under 7 % of its face's capacity (35/33/28 deg: 5.2 %; 45/40/30: 6.0 %)
// crept on the implicit solver until model revision 2026-12-06.14, more than 1 mm within 1.5 s in
// 7 of 16 runs (5-200 m, steps of 0.02-0.1 L/c), its rear corner opening and closing as the upper
// block slid off: the impacts stage met the corner with DDA's r0' rather than the rotation that
// carries the block's angular momentum (docs/theory.md §7a). Measured since: the 16 narrow holds
// within 5.9e-3 of the closed form, none stopped (2026-12-06).
TEST(LandslideBlocks, ALowerBlockHeldNarrowlyStaysUnderAWeakerJointImplicit) {
  expect_weak_joint_stack(Integrator::Implicit, kFirstWeakJointClass, held_narrowly);
  expect_weak_joint_stack(Integrator::Implicit, kWideWeakJointClass, held_narrowly);
}

}  // namespace
}  // namespace ddafit
