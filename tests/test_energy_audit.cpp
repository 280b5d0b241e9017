// The run's energy audit (forward/common/energy_check.hpp) counts gravity's work with each
// block's mass and centroid of t = 0. Until model revision 2026-11-28.3 it took the
// potential energy -sum m g . x with each block's current mass, density x area: strain
// changes the area, and that change times m g y depends on where the origin is. On the
// implicit Vajont section I run (elevations near 1000 m) the blocks swelled by 5.5 m^2 in all
// in the first 0.1 s, which read as 1.3e8 J/m of potential energy gained, and the slide's own
// kinetic energy then looked created (8 of 8 ensemble members stopped at t = 0.22 s once a
// contact rule had moved them slightly).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "forward/block_system.hpp"
#include "forward/common/displace_block.hpp"
#include "forward/common/energy_check.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

// One free 2 x 1 m rock block whose lower left corner is at `origin`, on a fixed floor.
BlockSystem block_at(const Vec2& origin) {
  Scene scene = verification::rock_scene(2500.0, 30.0, 1.0, 0.01, 0.01);
  const Vec2 o = origin;
  scene.blocks.push_back(
      verification::block("floor", {o + Vec2(-5, -1), o + Vec2(7, -1), o + Vec2(7, 0), o + Vec2(-5, 0)}, true));
  scene.blocks.push_back(verification::block("block", {o, o + Vec2(2, 0), o + Vec2(2, 1), o + Vec2(0, 1)}, false));
  return build_block_system(scene);
}

// A block that sinks by 0.1 m while its area swells by 2e-4 (a volumetric strain of 1e-4 in
// each direction): gravity's work is its t = 0 weight times the fall, 5000 kg/m x 9.81 x 0.1
// = 4905 J/m, at any elevation. Relative tolerance 1e-9: the only difference between the
// elevations is rounding in the centroid (1e4 m against 0.1 m of move: 1e-12 relative).
// The old rule's answer at 1e4 m: 4905 - 5000 x 2e-4 x 9.81 x 1e4 = -9.3e4 J/m.
TEST(EnergyAudit, GravitysWorkDoesNotDependOnWhereTheOriginIs) {
  const Vec2 gravity(0.0, -9.81);
  for (const double elevation : {0.0, 1000.0, 1.0e4}) {
    BlockSystem s = block_at(Vec2(300.0, elevation));
    const EnergyAudit audit = start_energy_audit(s, gravity);
    const int b = 1;
    ASSERT_FALSE(s.blocks[b].fixed);
    const double mass = s.mass(b);
    Vec6 d = Vec6::Zero();
    d << 0.0, -0.1, 0.0, 1e-4, 1e-4, 0.0;  // u0, v0, r0, eps_x, eps_y, gamma_xy
    displace_block(s, b, d, true);
    EXPECT_GT(s.mass(b), mass * (1.0 + 1.5e-4)) << "the strain swells the block";
    const double expected = mass * 9.81 * 0.1;
    EXPECT_NEAR(released_energy(audit, s, gravity), expected, 1e-9 * expected) << "at y = " << elevation << " m";
    EXPECT_TRUE(check_energy(audit, s, gravity).empty());
  }
}

// Two free 2 x 1 m rock blocks side by side on a fixed floor (5000 kg/m each).
BlockSystem two_blocks() {
  Scene scene = verification::rock_scene(2500.0, 30.0, 1.0, 0.01, 0.01);
  scene.blocks.push_back(verification::block("floor", {{-5, -1}, {7, -1}, {7, 0}, {-5, 0}}, true));
  scene.blocks.push_back(verification::block("lifted", {{0, 0}, {2, 0}, {2, 1}, {0, 1}}, false));
  scene.blocks.push_back(verification::block("sunk", {{2, 0}, {4, 0}, {4, 1}, {2, 1}}, false));
  return build_block_system(scene);
}

// What the starting overlaps store (EnergyAudit::stored_contact) may pay for lifting blocks, and
// for nothing else. One block lifted 1 mm by its contacts opening (49.05 J/m gained), the other
// sunk 1 mm (49.05 J/m released) and moving at 0.126 m/s (40 J/m): gravity's work is nil, so
// without a store 40 J/m is created (the allowance is 5 % of the scale, |work| + floor: 2.9 J/m).
// A store of 100 J/m pays for the lift, and the sunk block's 49 J/m covers its 40 J/m. A store of
// 10 J/m pays for a fifth of the lift only; and however large, it does not pay for motion: the
// lifted block moving at 0.126 m/s too (80 J/m in all) is energy created.
TEST(EnergyAudit, TheStartingOverlapsMayPayForLiftingBlocksAndNothingElse) {
  const Vec2 gravity(0.0, -9.81);
  BlockSystem s = two_blocks();
  EnergyAudit audit = start_energy_audit(s, gravity);
  const int lifted = 1, sunk = 2;
  Vec6 d = Vec6::Zero();
  d[1] = 1e-3;
  displace_block(s, lifted, d, true);
  d[1] = -1e-3;
  displace_block(s, sunk, d, true);
  const double mass = s.mass(sunk);
  ASSERT_NEAR(lifted_energy(audit, s, gravity), mass * 9.81 * 1e-3, 1e-6 * mass);
  ASSERT_NEAR(released_energy(audit, s, gravity), 0.0, 1e-6 * mass);
  const double speed = std::sqrt(2.0 * 40.0 / mass);
  s.blocks[sunk].velocity[0] = speed;
  EXPECT_FALSE(check_energy(audit, s, gravity).empty()) << "no store: 40 J/m is created";
  audit.stored_contact = 100.0;
  EXPECT_TRUE(check_energy(audit, s, gravity).empty()) << "the store pays for the lift";
  audit.stored_contact = 10.0;
  EXPECT_FALSE(check_energy(audit, s, gravity).empty()) << "a store of 10 J/m pays for a fifth of the lift";
  audit.stored_contact = 1e6;
  s.blocks[lifted].velocity[0] = speed;
  const std::string diagnosis = check_energy(audit, s, gravity);
  EXPECT_NE(diagnosis.find("creating energy"), std::string::npos) << "the store does not pay for motion";
}

}  // namespace
}  // namespace ddafit
