// A sliver crushed inside a large impact. Found on Vajont section VIII degraded (model revision
// 2026-11-28.8): a 1.7 m sliver between two blocks of a sliding mass, whose impact group held
// about 7,000 manifolds, closed at 3 m/s for 0.08 s and overlapped its neighbour by 1.15 % of
// its size. Groups of more than 160 contact points were left whole to the sweeps, and two
// Gauss-Seidel sweeps hand little of a heavy block's impact through a light one; since .29.1
// such a group is solved in pieces around its deepest points (converge_impacts.cpp,
// converge_pieces).
//
// The scene: a row of 1 m blocks resting on a fixed floor, a thin sliver on the middle one, and
// a row of 1 x 2 m blocks as long falling onto both at `speed` from 0.3 m above the sliver. Two
// rows of 12 are ~130 contact points in one impact, of 24 ~270: under and over the 160 points a
// group is solved whole up to. Swept over speeds, sliver thicknesses (mass ratio of an upper
// block to the sliver 28-110), row lengths and both default steps, on both solvers.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

BlockInput rectangle(const std::string& name, double x0, double y0, double x1, double y1, bool fixed) {
  return verification::block(name, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, fixed);
}

struct Crush {
  double speed;      // m/s, the upper row's at the start
  double thickness;  // m, the sliver's (0.6 m long)
  int count;         // blocks per row
  double step;       // s
  int substeps;
  Integrator integrator;
};

std::string label(const Crush& c) {
  char text[200];
  std::snprintf(text, sizeof text, "%s: rows of %d, %g m sliver, %g m/s, %g ms x %d",
                c.integrator == Integrator::Implicit ? "implicit" : "substep", c.count, c.thickness, c.speed,
                c.step * 1000, c.substeps);
  return text;
}

Scene crush_scene(const Crush& c) {
  Scene s = verification::rock_scene(2500.0, 30.0, 0.6, c.step, 0.05);
  s.options.integrator = c.integrator;
  s.options.substeps = c.substeps;
  const double half = 0.5 * c.count;
  s.blocks.push_back(rectangle("floor", -half - 2.0, -1.0, half + 2.0, 0.0, true));
  for (int i = 0; i < c.count; ++i)
    s.blocks.push_back(rectangle("lower_" + std::to_string(i), i - half, 0.0, i + 1 - half, 1.0, false));
  const double middle = (c.count / 2) + 0.5 - half;  // the centre of the middle lower block
  s.blocks.push_back(rectangle("sliver", middle - 0.3, 1.0, middle + 0.3, 1.0 + c.thickness, false));
  const double bottom = 1.0 + c.thickness + 0.3;
  for (int i = 0; i < c.count; ++i) {
    BlockInput upper = rectangle("upper_" + std::to_string(i), i - half, bottom, i + 1 - half, bottom + 2.0, false);
    upper.velocity = Vec2(0.0, -c.speed);
    s.blocks.push_back(upper);
  }
  return s;
}

// Runs the 36 crushes of one solver; returns the worst overlap (of the smaller block) and the
// run it came from, and counts the runs that did not complete or overlapped beyond 1 %.
struct Crushes {
  double worst = 0.0;
  std::string worst_case;
  int runs = 0, failed = 0;
};

Crushes crush_all(Integrator integrator) {
  Crushes out;
  for (const double speed : {3.0, 6.0, 10.0})
    for (const double thickness : {0.03, 0.06, 0.12})
      for (const int count : {12, 24})
        for (const auto& [step, substeps] : {std::pair{0.01, 3}, std::pair{0.005, 4}}) {
          const Crush c{speed, thickness, count, step, substeps, integrator};
          const SimulationResult r = simulate(crush_scene(c));
          const double ratio = r.summary.solver.worst_penetration_ratio;
          const bool ok = r.summary.status == RunStatus::Completed && ratio <= 0.01;
          EXPECT_TRUE(ok) << label(c) << ": " << r.summary.message << " overlap " << ratio << " between "
                          << r.summary.solver.worst_penetration_at;
          out.failed += ok ? 0 : 1;
          if (ratio > out.worst) out.worst = ratio, out.worst_case = label(c);
          ++out.runs;
        }
  std::printf("[measured] worst overlap %.4g of the smaller block (%s); %d of %d runs failed\n", out.worst,
              out.worst_case.c_str(), out.failed, out.runs);
  return out;
}

// Within 1 % of the smaller block, the bound Vajont's runs are held to (issue 25): 0.40 %
// worst. This scene does not reproduce section VIII's crush (the falling row is stopped in one
// impact, not driven on by a sliding mass): .28.7, which left groups over 160 points whole to the
// sweeps, passed it too (0.40 %). It guards the class of a light block in a large impact.
TEST(CrushedSliver, ASliverUnderAFallingRowStaysOutOfItsNeighboursSubstep) {
  EXPECT_EQ(crush_all(Integrator::Substep).runs, 36);
}

// Until revision 2026-11-29.3 the implicit solver failed 15 of the 36: its settling at t = 0
// moved every block that touched another, and the upper row (its blocks side by side, in
// flight) was dropped into the lower one before the clock ran (common/supported_blocks.hpp).
// Since then it settles only blocks resting on the ground: 36 of 36, 0.009 % worst.
TEST(CrushedSliver, ASliverUnderAFallingRowStaysOutOfItsNeighboursImplicit) {
  EXPECT_EQ(crush_all(Integrator::Implicit).runs, 36);
}

}  // namespace
}  // namespace ddafit
