// Blocks resting on fixed plates much thinner than themselves (a slide's base drawn as a thin
// layer, a geotextile, a concrete slab under a large block): the block stays where it rests. The
// class: square blocks of 2, 20 and 200 m on plates 0.001, 0.005 and 0.02 of their side thick,
// on faces of 0 and 35 deg (friction 38.5 deg), at a step of 0.05 L/c, 0.3 s, both solvers.
//
// Until model revision 2026-12-06.10 every block on a plate of 0.005 of its side or thinner fell
// freely for about 0.2 s at t = 0 (moving 6e-4 to 4e-3 of its side, and two implicit runs
// stopped): the flush tolerance eta, 0.02 of the free block's size (4 m for the 200 m block),
// exceeded the plate's thickness, and the face growing of manifold.cpp (vertices within eta / 4
// of one line make one face) grew the plate's top, end and bottom faces into one face along its
// diagonal, which read the block 0.5 m above it. eta is now at most half the least width of a
// fixed piece (forward/contact/collide.cpp). Tolerance: 1e-6 of the side (measured after:
// 3.6e-16 substep, 9.7e-8 implicit, its elastic settling after t = 0; a fall moves 6e-4 or more).
#include <cmath>
#include <iostream>
#include <string>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

void expect_blocks_on_thin_plates_stay(Integrator integrator) {
  double worst = 0.0;
  for (const double side : {2.0, 20.0, 200.0})
    for (const double thickness : {0.001, 0.005, 0.02})
      for (const double slope_angle : {0.0, 35.0}) {
        const double c = std::sqrt(5.0e9 / kRockDensity);
        Scene s = base_scene(0.3, 0.05 * side / c, 0.1, integrator);
        add_interface(s, "plate", 38.5);
        s.default_interface = 0;
        const Slope slope(slope_angle);
        const double t = thickness * side;
        s.blocks.push_back(
            block("plate", {slope.at(0, 0), slope.at(0, -t), slope.at(4 * side, -t), slope.at(4 * side, 0)}, true));
        s.blocks.push_back(block("block", box(slope.at(side, 0), slope.along, slope.up, side, side), false));
        s.measure.push_back({"centre", slope.at(1.5 * side, 0.5 * side)});
        const SimulationResult r = simulate(s);
        std::ostringstream label;
        label << name_of(integrator) << ": " << side << " m block on a plate " << t << " m thick, " << slope_angle
              << " deg";
        ASSERT_EQ(r.summary.status, RunStatus::Completed) << label.str() << ": " << r.summary.message;
        double largest = 0.0;
        for (const HistoryRow& row : r.history) largest = std::max(largest, row.displacement.norm());
        EXPECT_LT(largest / side, 1e-6) << label.str();
        worst = std::max(worst, largest / side);
      }
  std::cout << "[measured] " << name_of(integrator) << ", blocks on thin plates: worst move " << worst
            << " of their side\n";
}

TEST(ThinPlates, ABlockOnAPlateMuchThinnerThanItselfStaysImplicit) {
  expect_blocks_on_thin_plates_stay(Integrator::Implicit);
}

TEST(ThinPlates, ABlockOnAPlateMuchThinnerThanItselfStaysSubstep) {
  expect_blocks_on_thin_plates_stay(Integrator::Substep);
}

}  // namespace
}  // namespace ddafit
