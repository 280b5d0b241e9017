// Blocks in flight at t = 0 start exactly where the scene puts them, on both solvers.
//
// Before the clock runs, each solver lets the contacts touching at t = 0 take up the weight
// (the implicit solver's settling passes, the substep solver's quiet start). Only blocks
// resting on the ground may move there: joined to a fixed block through touching contacts,
// directly or through other touching blocks (forward/common/supported_blocks.hpp). Until
// revision 2026-11-29.3 any block touching another counted, so a row of blocks side by side
// in the air was dropped before t = 0: by 0.43 m into the row beneath on the implicit solver
// (tests/test_crushed_sliver.cpp). Here a row (or a stack of two rows) of touching blocks is
// held in the air above a row resting on a fixed floor, swept over row lengths, block sizes,
// heights (inside and beyond the contact margin), given speeds, steps and both solvers; the
// blocks in flight must be where they were put at the first output (t = 0) to 1e-9 of their
// size (round-off of the centroid's recomputation), and the resting row within 1e-4 of its
// size (it settles elastically under its weight: microns).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

struct Flight {
  int count;       // blocks per row
  double size;     // m, the blocks' side
  double height;   // m, the gap under the flying row, in block sizes
  double speed;    // m/s, downward, given to the flying blocks
  bool stacked;    // a second flying row on the first
  double step;     // s
  Integrator integrator;
};

std::string label(const Flight& f) {
  char text[200];
  std::snprintf(text, sizeof text, "%s: %d x %g m blocks%s, %g sizes up, %g m/s, %g ms",
                f.integrator == Integrator::Implicit ? "implicit" : "substep", f.count, f.size,
                f.stacked ? " (two rows)" : "", f.height, f.speed, f.step * 1000);
  return text;
}

BlockInput square(const std::string& name, double x0, double y0, double side, bool fixed) {
  return verification::block(name, {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}}, fixed);
}

TEST(FlightStart, BlocksInFlightStartWhereTheSceneHasThem) {
  int runs = 0;
  for (const Integrator integrator : {Integrator::Implicit, Integrator::Substep})
    for (const int count : {1, 2, 8, 24})
      for (const double size : {0.5, 4.0})
        for (const double height : {0.01, 0.3})
          for (const double speed : {0.0, 5.0})
            for (const bool stacked : {false, true})
              for (const double step : {0.01, 0.005}) {
                if (count == 1 && !stacked) continue;  // a lone block touches nothing: no cluster
                const Flight f{count, size, height, speed, stacked, step, integrator};
                Scene s = verification::rock_scene(2500.0, 30.0, 0.02, step, 0.01);
                s.options.integrator = integrator;
                const double w = count * size;
                s.blocks.push_back(verification::block("floor", {{-size, -size}, {w + size, -size}, {w + size, 0.0}, {-size, 0.0}}, true));
                for (int i = 0; i < count; ++i) s.blocks.push_back(square("rest_" + std::to_string(i), i * size, 0.0, size, false));
                const double bottom = size + height * size;
                std::vector<std::string> flying;
                for (int row = 0; row < (stacked ? 2 : 1); ++row)
                  for (int i = 0; i < count; ++i) {
                    BlockInput b = square("fly_" + std::to_string(row) + "_" + std::to_string(i), i * size,
                                          bottom + row * size, size, false);
                    b.velocity = Vec2(0.0, -speed);
                    flying.push_back(b.name);
                    s.blocks.push_back(b);
                  }
                bool seen = false;
                double worst_flying = 0.0, worst_resting = 0.0;
                SimulationHooks hooks;
                hooks.on_output = [&](double time, const BlockSystem& system) {
                  if (seen || time > 0.0) return;
                  seen = true;
                  for (size_t b = 0; b < system.blocks.size(); ++b) {
                    const std::string& name = system.block_names[b];
                    if (name == "floor") continue;
                    const bool flies = name.rfind("fly_", 0) == 0;
                    // Where the scene put it: column i, at the rest row or row r of the flyers.
                    const int i = std::stoi(name.substr(name.rfind('_') + 1));
                    const int r = flies ? std::stoi(name.substr(4, 1)) : 0;
                    const Vec2 given((i + 0.5) * size, flies ? bottom + (r + 0.5) * size : 0.5 * size);
                    const double off = (system.blocks[b].centroid - given).norm() / size;
                    (flies ? worst_flying : worst_resting) = std::max(flies ? worst_flying : worst_resting, off);
                  }
                };
                const SimulationResult r = simulate(s, hooks);
                ++runs;
                EXPECT_EQ(r.summary.status, RunStatus::Completed) << label(f) << ": " << r.summary.message;
                EXPECT_TRUE(seen) << label(f);
                EXPECT_LE(worst_flying, 1e-9) << label(f) << ": a block in flight moved before t = 0";
                EXPECT_LE(worst_resting, 1e-4) << label(f) << ": the resting row moved before t = 0";
              }
  EXPECT_EQ(runs, 2 * (4 * 2 * 2 * 2 * 2 * 2 - 2 * 2 * 2 * 2));
}

}  // namespace
}  // namespace ddafit
