// A fast block stopped by a contact must stop at the contact. Found on Vajont section VII
// degraded with split impulses (model revision 2026-11-27.3): a block rotating into its
// neighbour at 14 m/s was stopped by the contact, but the substep's trapezoidal move
// h (v0 + v1) / 2 still carried it h |v0| / 2 = 2 cm into the neighbour, 1 % of the smaller
// block. Since .27.4 the move after an impact follows the velocity after it (docs/theory.md
// §13, "Split impulses", step 5). Swept over block sizes, speeds, steps and what is hit (the
// fixed floor, a resting block as large, a resting block a quarter as large), square-on and
// corner first, because the depth an impact reaches depends on where within a substep the
// contact is met.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

// A w x h box centred at `centre`, turned by `angle` (radians).
BlockInput box(const std::string& name, Vec2 centre, double w, double h, double angle, bool fixed) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Vec2> corners;
  for (const Vec2& p : {Vec2(-0.5 * w, -0.5 * h), Vec2(0.5 * w, -0.5 * h), Vec2(0.5 * w, 0.5 * h), Vec2(-0.5 * w, 0.5 * h)})
    corners.push_back(centre + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
  return verification::block(name, corners, fixed);
}

enum class Target { Floor, SameSize, Quarter };

struct Impact {
  double size;      // m, the falling block is size x size / 2
  double speed;     // m/s, downward at the start, 0.5 m above what it hits
  double step;      // s
  int substeps;
  Target target;
  bool corner_first;  // turned 20 degrees: a corner meets the target first
};

std::string label(const Impact& c) {
  const char* target = c.target == Target::Floor ? "the floor" : c.target == Target::SameSize ? "a block as large" : "a quarter-size block";
  char text[160];
  std::snprintf(text, sizeof text, "%g m block at %g m/s onto %s, %g ms x %d%s", c.size, c.speed, target, c.step * 1000,
                c.substeps, c.corner_first ? ", corner first" : "");
  return text;
}

Scene impact_scene(const Impact& c) {
  Scene s = verification::rock_scene(2500.0, 30.0, 0.5, c.step, 0.05);
  s.options.integrator = Integrator::Substep;
  s.options.substeps = c.substeps;
  const double w = c.size;
  s.blocks.push_back(box("floor", {0.0, -0.5 * w}, 8.0 * w, w, 0.0, true));
  double top = 0.0;  // m, the height of what the block falls onto
  if (c.target != Target::Floor) {
    const double tw = c.target == Target::SameSize ? w : 0.25 * w;
    s.blocks.push_back(box("target", {0.0, 0.25 * tw}, tw, 0.5 * tw, 0.0, false));
    top = 0.5 * tw;
  }
  const double angle = c.corner_first ? 20.0 * M_PI / 180.0 : 0.0;
  // The lowest point of the turned block 0.5 m above the target.
  const double reach = 0.5 * (w * std::sin(angle) + 0.5 * w * std::cos(angle));
  BlockInput falling = box("falling", {0.0, top + 0.5 + reach}, w, 0.5 * w, angle, false);
  falling.velocity = Vec2(0.0, -c.speed);
  s.blocks.push_back(falling);
  s.measure.push_back({"falling", {0.0, top + 0.5 + reach}});
  return s;
}

// The deepest overlap stays within 0.5 % of the smaller block: a tenth of what the plain
// trapezoid gave Vajont's impact, and above the slop (1e-3 of a step's largest move) and the
// h^2 g that the rule still lets a stopped block move (at most 0.1 mm here).
constexpr double kMaxImpactOverlap = 0.005;

// Runs every impact of the sweep onto `targets`; returns how many ran.
int run_impacts(std::initializer_list<Target> targets, double max_overlap) {
  int runs = 0;
  double worst = 0.0;
  std::string worst_case;
  for (const double size : {1.0, 4.0, 8.0})
    for (const double speed : {5.0, 10.0, 20.0})
      for (const auto& [step, substeps] : {std::pair{0.01, 3}, std::pair{0.005, 4}})
        for (const Target target : targets)
          for (const bool corner : {false, true}) {
            const Impact c{size, speed, step, substeps, target, corner};
            const SimulationResult r = simulate(impact_scene(c));
            EXPECT_EQ(r.summary.status, RunStatus::Completed) << label(c) << ": " << r.summary.message;
            EXPECT_LE(r.summary.solver.worst_penetration_ratio, max_overlap)
                << label(c) << ": " << r.summary.solver.worst_penetration << " m between "
                << r.summary.solver.worst_penetration_at;
            if (r.summary.solver.worst_penetration_ratio > worst)
              worst = r.summary.solver.worst_penetration_ratio, worst_case = label(c);
            ++runs;
          }
  std::printf("[measured] worst overlap %.4g of the smaller block (%s)\n", worst, worst_case.c_str());
  return runs;
}

// Onto the fixed floor and onto a resting block as large: 72 impacts. With the trapezoidal
// move of revision .27.3 (kSmoothAccelerationRatio 0) 7 of them overlapped by more than
// 0.5 %, up to 1.01 % (a 1 m block at 10-20 m/s).
TEST(ImpactDepth, AFastBlockStopsAtWhatItHits) {
  EXPECT_EQ(run_impacts({Target::Floor, Target::SameSize}, kMaxImpactOverlap), 72);
}

// A light block squeezed between a heavy one arriving fast and the fixed floor (mass ratio
// 16): held within 1 % of its size, the bound Vajont's runs are held to. Gauss-Seidel gains
// ~1/(1 + mass ratio) of the error per sweep, so the sweeps leave it sinking; the step's
// position correction takes it out. Until revision 2026-11-27.6 the correction stopped after
// eight passes while a pass was still correcting: up to 1.9 % (1 m block at 20 m/s onto a
// 0.25 m one, 10 ms x 3; 14 of 36 above 0.5 %). With up to sixteen while one still corrects,
// 0.67 % (2 of 36 above 0.5 %, the bound of the impacts above; not reached here).
TEST(ImpactDepth, ALightBlockSqueezedOntoTheFloorStaysOutOfIt) {
  EXPECT_EQ(run_impacts({Target::Quarter}, 2.0 * kMaxImpactOverlap), 36);
}

}  // namespace
}  // namespace ddafit
