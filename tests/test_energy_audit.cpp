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

// What the starting overlaps store (EnergyAudit::stored_contact) may come back as motion, and
// no more. The 5000 kg/m block, lifted 1 mm by its contacts opening (-49.05 J/m of gravity's
// work) and moving at 0.126 m/s (40 J/m): without a store the budget is spent and 40 J/m is
// created (the allowance is 5 % of the scale, |work| + floor: 3.9 J/m); a store of 100 J/m
// covers it; at 0.283 m/s (200 J/m) the store's 51 J/m left over and the 8.9 J/m allowance
// do not, and the diagnosis names the block.
TEST(EnergyAudit, TheStartingOverlapsMayGiveBackWhatTheyStoreAndNoMore) {
  const Vec2 gravity(0.0, -9.81);
  BlockSystem s = block_at(Vec2(0.0, 0.0));
  EnergyAudit audit = start_energy_audit(s, gravity);
  const int b = 1;
  Vec6 d = Vec6::Zero();
  d[1] = 1e-3;
  displace_block(s, b, d, true);
  const double mass = s.mass(b);
  ASSERT_NEAR(released_energy(audit, s, gravity), -mass * 9.81 * 1e-3, 1e-6 * mass);
  s.blocks[b].velocity[0] = std::sqrt(2.0 * 40.0 / mass);
  EXPECT_FALSE(check_energy(audit, s, gravity).empty()) << "no store: 40 J/m is created";
  audit.stored_contact = 100.0;
  EXPECT_TRUE(check_energy(audit, s, gravity).empty()) << "the store covers 40 J/m";
  s.blocks[b].velocity[0] = std::sqrt(2.0 * 200.0 / mass);
  const std::string diagnosis = check_energy(audit, s, gravity);
  EXPECT_NE(diagnosis.find("creating energy"), std::string::npos) << diagnosis;
  EXPECT_NE(diagnosis.find("'block'"), std::string::npos) << diagnosis;
}

}  // namespace
}  // namespace ddafit
