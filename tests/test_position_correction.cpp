// The substep solver's position correction (forward/substep/solve_contacts.hpp,
// correct_positions): a correction that moves a block into a neighbour the deep list did not
// hold must correct that overlap too. Regression of Vajont section III degraded (model
// revision 2026-11-26.1): slide_00446, pinched between blocks twelve times heavier, was
// corrected out of one and pressed 5-6 cm (1.1 % of its size) into slide_00451.
#include <gtest/gtest.h>

#include <vector>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {
namespace {

// A row of unit blocks along x touching face to face, the last one fixed: manifold k joins
// block k and k + 1 with one point on the x axis (so no turning), normal +x.
struct Row {
  std::vector<ContactManifold> manifolds;
  SweepState state;
};

Row make_row(const std::vector<double>& separations, double deep_overlap) {
  Row row;
  const int blocks = static_cast<int>(separations.size()) + 1;
  row.state.velocity.assign(blocks, Vec3::Zero());
  row.state.step_moves.assign(blocks, Vec3::Zero());
  row.state.masses.assign(blocks - 1, BlockMass{1.0, 1.0, true});
  row.state.masses.push_back(BlockMass{});  // fixed
  for (int k = 0; k + 1 < blocks; ++k) {
    ContactManifold m;
    m.block_a = k;
    m.block_b = k + 1;
    m.point_count = 1;
    m.normal = Vec2(1.0, 0.0);
    m.tangent = Vec2(0.0, -1.0);
    m.deep_overlap = deep_overlap;
    m.points[0].ra = Vec2(0.5, 0.0);
    m.points[0].rb = Vec2(-0.5, 0.0);
    m.points[0].separation = separations[k];
    row.manifolds.push_back(m);
  }
  row.state.deep.assign(row.manifolds.size(), 0);
  return row;
}

TEST(PositionCorrection, ABlockPushedIntoANeighbourOutsideTheListIsCorrectedToo) {
  // X | Y | Z | W (fixed): X and Y overlap 0.104 m, flagged deep by a relax sweep; Y-Z and Z-W
  // touch. Only X and Y are involved at first, so the list holds X-Y and Y-Z; correcting Y
  // out of X pushes it into Z, and correcting Y-Z pushes Z into the fixed W, whose manifold
  // the list did not hold: Z kept 0.027 m beyond the deep overlap in W before the fix.
  constexpr double kDeep = 0.004;
  Row row = make_row({-0.104, 0.0, 0.0}, kDeep);
  row.state.deep[0] = 1;
  correct_positions(row.manifolds, PositionCorrection{8, 8, 0.8, 1.0}, row.state);
  for (size_t k = 0; k < row.manifolds.size(); ++k) {
    const ContactManifold& m = row.manifolds[k];
    const double gap = current_gap(m, m.points[0], row.state.step_moves);
    // Eight passes at 0.8 of the excess converge along a row with a fixed end as
    // Gauss-Seidel does on a chain: at most 6 mm of the 100 mm excess is left (measured),
    // so every manifold keeps under a tenth of it.
    EXPECT_GT(gap, -(kDeep + 0.01)) << "manifold " << k;
  }
  // The fixed block does not move, and the overlap went out through the free ones.
  EXPECT_EQ(row.state.step_moves.back(), Vec3::Zero());
  EXPECT_LT(row.state.step_moves[0].x(), -0.05);
}

TEST(PositionCorrection, NothingMovesWithoutADeepOverlap) {
  Row row = make_row({-0.003, 0.0, -0.001}, 0.004);
  correct_positions(row.manifolds, PositionCorrection{8, 8, 0.8, 1.0}, row.state);
  for (const Vec3& move : row.state.step_moves) EXPECT_EQ(move, Vec3::Zero());
}

}  // namespace
}  // namespace ddafit
