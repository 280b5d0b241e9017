// Blocks held by their friction on a slope stay where they are (seed §2.3's incline with
// tan(phi) above tan(alpha)). The class: blocks 2, 20 and 200 m long, H / L of 0.25, 0.5 and 1, on
// faces of 20 and 35 deg, held by margins of 1, 3, 6 and 12 % of the face's capacity (tan(phi) =
// tan(alpha) / (1 - margin)), at steps of 0.02, 0.05 and 0.2 of the block's elastic period L/c
// (L = sqrt(area), c = sqrt(E/rho)); 2 s each, from rest. A held block's corners share its weight
// unevenly (the rear one carries less: 0.41 of it for H / L = 0.25 on 35 deg), so the settled
// shear of the rear corner can pass its own cap while the face holds.
//
// Tolerance: the block's centre moves less than 1e-4 of its length in 2 s (0.2 mm on a 2 m block);
// a held block should not move at all, and the substep solver moves none by more than 1e-13 of
// it (measured 2026-12-06).
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

struct HeldBlock {
  double length, height_ratio, slope, margin;
};

constexpr double kHeldTolerance = 1e-4;  // of the block's length

// `take` picks the cases of the class a test runs.
void expect_held_blocks_stay(Integrator integrator, const std::function<bool(const HeldBlock&)>& take,
                             const std::vector<double>& shares = {0.02, 0.05, 0.2}) {
  double worst = 0.0;
  int runs = 0, moved = 0;
  for (const double length : {2.0, 20.0, 200.0})
    for (const double ratio : {0.25, 0.5, 1.0})
      for (const double slope : {20.0, 35.0})
        for (const double margin : {0.01, 0.03, 0.06, 0.12})
          for (const double share : shares) {
            const HeldBlock h{length, ratio, slope, margin};
            if (!take(h)) continue;
            ++runs;
            Crossing c;
            c.slope = slope;
            c.friction = std::atan(std::tan(slope * kDegree) / (1.0 - margin)) / kDegree;
            c.length = length, c.height = ratio * length;
            c.spacing = 4.0 * length, c.front_gap = 2.0 * length;  // one base block
            Scene scene = crossing_scene(c, integrator);
            scene.duration = 2.0;
            set_step_share(scene, c, share);
            const SimulationResult r = simulate(scene);
            const std::string label = describe(c, integrator) + ", margin " + std::to_string(margin) + ", step " +
                                      std::to_string(share) + " L/c";
            ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
            double largest = 0.0;
            for (const HistoryRow& row : r.history) largest = std::max(largest, row.displacement.norm());
            EXPECT_LT(largest / length, kHeldTolerance) << label;
            if (largest / length >= kHeldTolerance) ++moved;
            worst = std::max(worst, largest / length);
          }
  std::cout << "[measured] " << name_of(integrator) << ", " << runs << " held blocks: " << moved
            << " moved more than 1e-4 of their length, worst " << worst << "\n";
}

bool flat(const HeldBlock& h) { return h.height_ratio < 0.5; }

// The substep solver has no elastic period to resolve: two of the steps (0.02 L/c, 68 000 steps for
// a 2 m block, would take most of a minute).
TEST(HeldBlocks, BlocksHeldByTheirFrictionStaySubstep) {
  expect_held_blocks_stay(Integrator::Substep, [](const HeldBlock&) { return true; }, {0.05, 0.2});
}

// Until model revision 2026-12-06.11, 18 of these 144 crept more than 1e-4 of their length (up
// to 4.7e-4; measured on a base as thick as the block, since on this test's 1 m plate the 200 m
// blocks fell at t = 0 until revision .06.10, tests/test_thin_plates.cpp): the settling before
// t = 0 set the rear corner sliding at its cap, and a block whose group was held by its friction
// started out of balance (forward/step/settle_sliding.cpp, which now settles a held group with
// its points locked). Measured after it: worst 1.1e-5 (2026-12-06).
TEST(HeldBlocks, BlocksHeldByTheirFrictionStayImplicit) {
  expect_held_blocks_stay(Integrator::Implicit, [](const HeldBlock& h) { return !flat(h); });
}

// Flat blocks (H / L = 0.25) held on 35 deg faces crept on the implicit solver at steps of 0.05 L/c
// and under until model revision 2026-12-06.14: 20 of these 72 runs more than 1e-4 of their length
// (a 200 m block 0.15-0.30 m in 2 s). The rear corner, at its cap, slid while the front one stuck,
// and the block rocked onto its front corner and crept by stick-slip; neither a contact dashpot nor
// damping of the blocks' strain stopped it. The cause was the impacts stage, which met a point's
// velocity with DDA's r0' rather than the rotation that carries the block's angular momentum and so
// fed a strain mode at every step (forward/mass_matrix.hpp, momentum_rigid_velocity; docs/theory.md
// §7a). Measured since: 0 of 72, worst 2.4e-5 (2026-12-06).
TEST(HeldBlocks, FlatBlocksHeldByTheirFrictionStayImplicit) {
  expect_held_blocks_stay(Integrator::Implicit, flat);
}

// A square block held on a free plate that rests on a fixed face (both interfaces held by 12 % of
// their capacity: tan(phi) = tan(alpha) / 0.88): blocks of 2, 20 and 200 m on plates 0.02 and 0.2
// of their side thick and three times as long, on 20 and 35 deg, at 0.05 and 0.2 L/c, 1 s
// (slope_scene.hpp, block_on_free_plate). Neither should move; tolerance as above.
void expect_block_on_free_plate_stays(Integrator integrator) {
  int runs = 0, bad = 0;
  double worst = 0.0;
  for (const double side : {2.0, 20.0, 200.0})
    for (const double thickness : {0.02, 0.2})
      for (const double slope_angle : {20.0, 35.0})
        for (const double share : {0.05, 0.2}) {
          ++runs;
          const double t = thickness * side;
          const Scene s = block_on_free_plate({side, thickness, slope_angle, 0.88, 0.88, share}, integrator, 0.1);
          const SimulationResult r = simulate(s);
          std::ostringstream label;
          label << name_of(integrator) << ": " << side << " m block on a free plate " << t << " m thick, "
                << slope_angle << " deg, step " << share << " L/c";
          if (r.summary.status != RunStatus::Completed) {
            ADD_FAILURE() << label.str() << ": " << r.summary.message;
            ++bad;
            continue;
          }
          const double moved = held_or_sliding_error(r, slope_angle, 0.88, side);
          EXPECT_LT(moved, kHeldTolerance) << label.str();
          if (moved >= kHeldTolerance) ++bad;
          worst = std::max(worst, moved);
        }
  std::cout << "[measured] " << name_of(integrator) << ", " << runs << " blocks on free plates: " << bad
            << " stopped or moved more than 1e-4 of their side, worst completed " << worst << "\n";
}

TEST(HeldBlocks, ABlockOnAFreePlateStaysSubstep) { expect_block_on_free_plate_stays(Integrator::Substep); }

// Until model revision 2026-12-06.14 the implicit solver stopped 8 of these 24 on "contacts are
// creating energy", every one on 35 deg (5 within 12 steps), and the substep solver held all 24
// (worst 4.2e-7). Traced then to the settling's share of the block's shear between its corners;
// what set the block and plate ringing was the impacts stage's rigid velocity, as for the flat
// blocks above (docs/theory.md §7a). Measured since: 0 of 24, worst 6.7e-5 of the side (2026-12-06).
TEST(HeldBlocks, ABlockOnAFreePlateStaysImplicit) { expect_block_on_free_plate_stays(Integrator::Implicit); }

}  // namespace
}  // namespace ddafit
