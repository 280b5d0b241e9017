// Sliders across flush joints at the steps and speeds of a landslide run: every slider of
// test_joint_crossing.cpp's classes runs at the default 1 ms and at 0-4 m/s, while a Vajont
// section steps 10 ms x 3 and its mass runs at 15-30 m/s. Here sliders from rest at 5 and 10 ms
// (960 runs a solver) and sliders at 10 and 30 m/s at 1 and 10 ms (192 a solver), each on the
// slope descending to the right and on its mirror image (forward/mirror.hpp), both solvers, to
// test_joint_crossing.cpp's tolerance: 1 % of seed Eq. 4 wherever the slider has moved 1 cm.
#include <iostream>
#include <string>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

// Sliders from rest at coarse steps (5 and 10 ms), the start of every released slope: slopes
// of 10-40 deg, 1-8 deg steeper than the friction (a net acceleration down to 0.17 m/s^2),
// sliders of 0.5-3 m, joints every 0.08-2.5 m; 480 runs, each on the slope descending to the
// right and on its mirror image descending to the left (forward/mirror.hpp): the same physics met
// in another order by the sweeps (the substep solver's defect below fails by different amounts
// each way round; a class passed one way only is an instance). Until revision 2026-12-02.2 the
// implicit solver's first steps stopped at the pass limit with capped locks still letting go,
// and 73 of the 480 fell more than 1 % behind seed Eq. 4 (27 % worst: 10 deg, 7 deg friction, a
// 1.2 m slider over 0.08 m joints, 10 ms), a lag of about one step's worth of velocity that
// never closes (open_close_iterate.cpp, kStartingExtraPasses). Measured at .12.02.2: the
// implicit solver within 0.89 % descending to the right, 0.89 % to the left.
void expect_sliders_from_rest_follow_eq4_at_coarse_steps(Integrator integrator) {
  double worst = 0.0;
  std::string worst_label;
  for (const bool mirrored : {false, true})
    for (const double step : {0.005, 0.01})
      for (const double slope : {10.0, 20.0, 28.0, 35.0, 40.0})
        for (const double margin : {1.0, 3.0, 5.0, 8.0})
          for (const auto& [length, height] : {std::pair{0.5, 0.5}, std::pair{1.2, 0.6}, std::pair{3.0, 0.8}})
            for (const double spacing : {0.08, 0.3, 1.0, 2.5}) {
              Crossing c;
              c.slope = slope, c.friction = slope - margin, c.length = length, c.height = height;
              c.spacing = spacing, c.speed = 0.0, c.front_gap = 0.03;
              std::string label;
              const double error = expect_crossing_at_step(c, integrator, step, mirrored, label);
              if (error > worst) worst = error, worst_label = label;
            }
  std::cout << "[measured] 960 sliders from rest at 5 and 10 ms, both ways down: worst displacement error " << worst
            << " (" << worst_label << ")\n";
}

TEST(JointCrossingCoarseSteps, SlidersFromRestFollowSeedEq4Implicit) {
  expect_sliders_from_rest_follow_eq4_at_coarse_steps(Integrator::Implicit);
}

// Until model revision 2026-12-02.3 two of the 480 failed each way down, a 1.2 m and a 0.5 m
// slider on a 40 deg slope at 39 deg friction over 0.08 m joints at 10 ms x 4 (3.0 % and 1.9 %
// ahead of Eq. 4 descending to the right, 3.8 % and 2.9 % to the left): the rigid plank's two
// relax sweeps swung in a two-cycle, every substep ending with the rear sinking. The sweeps
// now meet the manifolds from the lowest up (prepare_contacts.hpp, colour_manifolds).
TEST(JointCrossingCoarseSteps, SlidersFromRestFollowSeedEq4Substep) {
  expect_sliders_from_rest_follow_eq4_at_coarse_steps(Integrator::Substep);
}

// Sliders at landslide speeds: a Vajont section's mass runs at 15-30 m/s across joints a few
// metres apart, and the sweeps above start at rest or at 2-4 m/s. Here 10 and 30 m/s, at 1 ms and
// at 10 ms (where the step control, not the scene's step, sets how far a step goes), on slopes
// that speed the slider up (28/18, 20/12, 35/33 deg) and one that slows it (10 deg at 20 deg
// friction, -1.8 m/s^2), sliders of 0.5-3 m over joints every 0.3 and 2.5 m, both ways down:
// 192 runs a solver, each within 1 % of seed Eq. 4 where it has moved 1 cm. Measured 2026-12-04
// over a wider sweep (10, 20 and 30 m/s, joints every 0.3, 1 and 2.5 m; 432 runs a solver): the
// substep solver within 2.0e-6 of Eq. 4, the implicit one within 1.3e-4.
void expect_fast_sliders_follow_eq4(Integrator integrator) {
  double worst = 0.0;
  std::string worst_label;
  const int runs = for_each_fast_slider({0.001, 0.01}, [&](const Crossing& c, double step, bool mirrored) {
    std::string label;
    const double error = expect_crossing_at_step(c, integrator, step, mirrored, label);
    if (error > worst) worst = error, worst_label = label;
  });
  EXPECT_EQ(runs, 192);
  std::cout << "[measured] " << runs << " sliders at 10 and 30 m/s, both ways down: worst displacement error "
            << worst << " (" << worst_label << ")\n";
}

TEST(JointCrossingFastSliders, SlidersAtLandslideSpeedsFollowSeedEq4Substep) {
  expect_fast_sliders_follow_eq4(Integrator::Substep);
}

TEST(JointCrossingFastSliders, SlidersAtLandslideSpeedsFollowSeedEq4Implicit) {
  expect_fast_sliders_follow_eq4(Integrator::Implicit);
}

}  // namespace
}  // namespace ddafit
