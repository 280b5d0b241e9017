// Housner's rocking block (G. W. Housner, "The behavior of inverted pendulum structures during
// earthquakes", Bull. Seismol. Soc. Am. 53(2), 1963): a rigid b x H block released from rest,
// tilted by theta0 about a base corner, falls back about that corner, strikes the floor with
// the other and rocks on, each impact leaving the angular velocity multiplied by
//     r = 1 - (3/2) sin^2(alpha),  alpha = atan(b / H)                          (Housner eq. 18)
// (angular momentum kept about the new corner; no bounce, no slip). Between impacts the energy
// is kept, so the peak tilts theta_k obey
//     cos(alpha - theta_{k+1}) - cos(alpha) = r^2 [cos(alpha - theta_k) - cos(alpha)],
// and the first impact comes after t1 = arccosh(alpha / (alpha - theta0)) / p with
// p = sqrt(3 g / (4 R)), R the half-diagonal (the linearised equation, Housner eq. 8).
// This is DDA's classic check (Yagoda-Biran & Hatzor 2010 ran it for Shi's DDA): the landing
// on a corner is the contact event of a toppling slope, and a rocking block that gains energy
// at its impacts would make one that keeps rocking or falls where it should stop.
//
// The class: aspect H/b 3, 4.5 and 6; base 0.5 and 2 m; tilt 0.3 and 0.6 of alpha; both
// solvers. Tolerances and why:
//   - the first impact within 3 % of t1 (the linearised equation is within 0.5 % of the exact
//     one at these tilts, and the step, 5 ms, is under 1 % of t1);
//   - the tilt at t = 0 within 1 % of the given one (settling and the quiet start must not
//     move a block that is not in equilibrium: the implicit solver's settling set it upright
//     until revision 2026-12-03.1, and it never rocked);
//   - each of the first three impacts keeps at most r^2 + 0.02 of the rocking energy (a
//     discretised impact may lose more than Housner's instantaneous one, never gain), and at
//     least r^2 - 0.12 (measured 0.003-0.019 below r^2 on the substep solver, 0.005-0.063 on
//     the implicit one: an impact that loses much more is damping the rocking out).
// A column of 2-14 equal blocks released the same way must come to rest (below).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "forward/simulation.hpp"
#include "forward/substep/quiet_start.hpp"
#include "verify/analytic.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

using verification::HousnerRocking;
using verification::RockingSetup;

struct Rocking {
  double base, height;  // b, H (m)
  double tilt_share;    // theta0 / alpha
  int blocks = 1;       // the column cut into this many equal blocks
  Integrator integrator;

  HousnerRocking housner() const { return {base, height}; }
  double tilt() const { return tilt_share * housner().alpha(); }  // theta0, rad
};

std::string label(const Rocking& c) {
  char text[160];
  std::snprintf(text, sizeof text, "%s: %g x %g m in %d block(s), tilted %.2f alpha",
                c.integrator == Integrator::Implicit ? "implicit" : "substep", c.base, c.height, c.blocks,
                c.tilt_share);
  return text;
}

// The column of verification::rocking_column_scene, 5 ms steps, on the solver of `c`.
SimulationResult rock(const Rocking& c, double duration) {
  Scene s = verification::rocking_column_scene(RockingSetup{c.base, c.height, c.tilt_share, c.blocks, duration});
  s.options.integrator = c.integrator;
  return simulate(s);
}

TEST(Rocking, ABlockReleasedOnItsCornerRocksAsHousnerSays) {
  for (const Integrator integrator : {Integrator::Substep, Integrator::Implicit}) {
    int runs = 0;
    double worst_gain = -1.0, worst_loss = 1.0, worst_time = 0.0;
    for (const double aspect : {3.0, 4.5, 6.0})
      for (const double base : {0.5, 2.0})
        for (const double share : {0.1, 0.3, 0.6}) {
          const Rocking c{base, aspect * base, share, 1, integrator};
          const HousnerRocking housner = c.housner();
          const double rr = housner.energy_kept(), t1 = housner.first_impact(c.tilt());
          // Long enough for four impacts: each half-cycle is shorter than the release's 2 t1.
          const SimulationResult run = rock(c, 8.0 * t1);
          ++runs;
          ASSERT_EQ(run.summary.status, RunStatus::Completed) << label(c) << ": " << run.summary.message;
          const verification::RockingTrace rec = verification::rocking_trace(run.history);
          ASSERT_GE(rec.peaks.size(), 4u) << label(c) << ": rocked " << rec.peaks.size() << " half-cycles";
          const double time_error = (rec.first_impact - t1) / t1;
          worst_time = std::max(worst_time, std::abs(time_error));
          EXPECT_NEAR(rec.first_impact, t1, 0.03 * t1) << label(c);
          EXPECT_NEAR(rec.peaks[0], c.tilt(), 0.01 * c.tilt()) << label(c) << ": the tilt at release";
          for (int k = 0; k < 3; ++k) {
            const double share_kept = housner.energy(rec.peaks[k + 1]) / housner.energy(rec.peaks[k]);
            worst_gain = std::max(worst_gain, share_kept - rr);
            worst_loss = std::min(worst_loss, share_kept - rr);
            EXPECT_LE(share_kept, rr + 0.02) << label(c) << ", impact " << k + 1;
            EXPECT_GE(share_kept, rr - 0.12) << label(c) << ", impact " << k + 1;
          }
        }
    std::printf("[measured] %s: %d releases; first impact within %.2f %% of Housner's t1; energy kept per impact "
                "r^2 %+.3f to %+.3f\n",
                integrator == Integrator::Implicit ? "implicit" : "substep", runs, 100.0 * worst_time, worst_loss,
                worst_gain);
  }
}

// Columns of 2, 4, 8 and 14 equal blocks (aspect 3 and 4.5, base 0.5 and 2 m, tilted 0.05, 0.2
// and 0.5 of alpha; 5 ms steps) released on a corner. Joints may open as the column rocks, so
// Housner's numbers are not the answer, but rocking only loses energy: each column must start
// at its given tilt (2 %) and be at rest (every point under 0.01 m/s over the last half-second,
// a tenth of the default rest_speed, as for the struck stacks) after twice the time Housner's
// single block takes to stop, plus 1 s.
struct ColumnRest {
  int runs = 0, moving = 0, stopped = 0;
  double worst = 0.0;
  std::string worst_case;
  double release_low = 1e9, release_high = -1e9;  // tilt at t = 0 / given tilt
};

ColumnRest columns_come_to_rest(Integrator integrator) {
  ColumnRest out;
  for (const int blocks : {2, 4, 8, 14})
    for (const double aspect : {3.0, 4.5})
      for (const double base : {0.5, 2.0})
        for (const double share : {0.05, 0.2, 0.5}) {
          const Rocking c{base, aspect * base, share, blocks, integrator};
          const double duration = 2.0 * c.housner().time_to_rest(c.tilt()) + 1.0;
          const SimulationResult r = rock(c, duration);
          ++out.runs;
          if (r.summary.status != RunStatus::Completed) {
            ++out.stopped;
            ADD_FAILURE() << label(c) << ": " << r.summary.message;
            continue;
          }
          double last = 0.0;
          for (const HistoryRow& h : r.history)
            if (h.time >= duration - 0.5) last = std::max(last, h.velocity.norm());
          // The tilt at t = 0 (base to top) against the given one.
          const Vec2 axis = r.history[1].position - r.history[0].position;
          const double release = std::atan2(axis.x(), axis.y()) / c.tilt();
          out.release_low = std::min(out.release_low, release);
          out.release_high = std::max(out.release_high, release);
          EXPECT_NEAR(release, 1.0, 0.02) << label(c) << ": the tilt at t = 0 against the given one";
          if (last >= 0.01) ++out.moving;
          if (last > out.worst) out.worst = last, out.worst_case = label(c);
        }
  std::printf("[measured] %d columns released on a corner: %d stopped by the energy audit, %d still moving at twice "
              "Housner's time to rest + 1 s; fastest %.3g m/s (%s); tilt at t = 0 %.4f-%.4f of the given\n",
              out.runs, out.stopped, out.moving, out.worst, out.worst_case.c_str(), out.release_low, out.release_high);
  return out;
}

TEST(Rocking, AColumnReleasedOnItsCornerComesToRestImplicit) {
  const ColumnRest r = columns_come_to_rest(Integrator::Implicit);
  EXPECT_EQ(r.moving, 0) << r.worst_case;
}

// KNOWN DEFECT (found 2026-12-03, revision .12.03.1): the substep solver leaves 21 of the 48
// columns rocking (0.16 m/s worst: fourteen 0.5 x 0.11 m blocks tilted 0.2 alpha; docs/theory.md
// §13, "A rocking column gains energy"), and its quiet start lets a column on a corner fall by up to 12 % of
// its tilt before t = 0. The single block (Housner's test above) rocks as Housner says.
TEST(Rocking, DISABLED_AColumnReleasedOnItsCornerComesToRestSubstep) {
  const ColumnRest r = columns_come_to_rest(Integrator::Substep);
  EXPECT_EQ(r.moving, 0) << r.worst_case;
}

// Settling before the clock runs must not move a block that is not in equilibrium, at any step a
// user may pick: a block tilted on its corner starts the run where it was given. The class:
// Housner blocks of base 0.1, 1 and 10 m, aspect H/b 3 and 6, tilted 0.1, 0.3 and 0.6 of alpha;
// steps of 20 ms to 0.5 s (one and four substeps on the substep solver). Bound: the tilt at t = 0
// within 2 % of the given one, or within 2e-3 rad (0.11 deg) of it: the substep solver's quiet
// start settles again at shorter steps only a block it turned by more than kQuietStartTurnLimit,
// 0.01 rad, and one that creeps less keeps what it crept (measured 1.6e-3 rad at most). Settling
// that lets a block fall turns it by its whole tilt, 0.016-0.2 rad here.
struct TiltedStart {
  int runs = 0, warned = 0;        // runs, and runs warned of a turn before t = 0 (known limit (k))
  std::vector<std::string> missed;  // runs off by more than the bound, with their labels
};

TiltedStart tilted_blocks_start_where_given(Integrator integrator) {
  TiltedStart out;
  double worst = 0.0, worst_turn = 0.0;
  std::string worst_case;
  for (const double base : {0.1, 1.0, 10.0})
    for (const double aspect : {3.0, 6.0})
      for (const double share : {0.1, 0.3, 0.6})
        for (const double step : {0.02, 0.05, 0.1, 0.2, 0.5})
          for (const int substeps : {1, 4}) {
            if (integrator == Integrator::Implicit && substeps > 1) continue;  // no substeps
            RockingSetup setup;
            setup.base = base;
            setup.height = aspect * base;
            setup.tilt_share = share;
            setup.step = step;
            setup.duration = step;
            Scene s = verification::rocking_column_scene(setup);
            s.options.substeps = substeps;
            s.options.integrator = integrator;
            const Rocking c{base, aspect * base, share, 1, integrator};
            char what[200];
            std::snprintf(what, sizeof what, "%s, %g s x %d", label(c).c_str(), step, substeps);
            double at_start = -1.0;
            SimulationHooks hooks;
            hooks.on_output = [&](double time, const BlockSystem& system) {
              if (time > 0.0 || at_start >= 0.0) return;
              const Block& block = system.blocks[1];
              const Vec2 edge = system.vertices[block.first_vertex + 1] - system.vertices[block.first_vertex];
              at_start = -std::atan2(edge.y(), edge.x());  // tilted clockwise: the base edge points down
            };
            const SimulationResult r = simulate(s, hooks);
            ++out.runs;
            for (const std::string& w : r.summary.warnings)
              out.warned += w.find("known limits (k)") != std::string::npos;
            if (r.summary.status != RunStatus::Completed) {
              out.missed.push_back(std::string(what) + ": " + r.summary.message);
              continue;
            }
            const double turned = std::abs(at_start - c.tilt()), error = turned / c.tilt();
            if (error > 0.02 && turned > 2e-3)
              out.missed.push_back(std::string(what) + ": tilt at t = 0 " + std::to_string(error) + " off");
            if (error > worst) worst = error, worst_case = what;
            worst_turn = std::max(worst_turn, turned);
          }
  std::printf("[measured] %d blocks released on a corner at 20 ms - 0.5 s: %zu missed; tilt at t = 0 at most %.3g off "
              "the given one (%s), at most %.3g rad; %d warned\n",
              out.runs, out.missed.size(), worst, worst_case.c_str(), worst_turn, out.warned);
  return out;
}

// The implicit solver's settling (docs/theory.md §6) holds a falling block where it was given: 90
// runs, every block exactly at its given tilt (measured 2026-12-06).
TEST(Rocking, ABlockReleasedOnItsCornerStartsWhereItWasGivenAtEveryStepImplicit) {
  const TiltedStart t = tilted_blocks_start_where_given(Integrator::Implicit);
  EXPECT_EQ(t.runs, 90);
  EXPECT_EQ(t.warned, 0);
  EXPECT_TRUE(t.missed.empty()) << t.missed.size() << " missed, the first: " << t.missed.front();
}

// The substep solver (docs/theory.md Known limits (k)). Until model revision 2026-12-06.2 its
// quiet start stepped the scene's own time.step from rest until the contacts' impulses stopped
// changing, a block resting on its corner turned in each step, and 129 of these 180 runs started
// with the block fallen onto its base (every 0.1 m block, 1 m blocks from 20-50 ms, 10 m blocks
// from 0.1-0.5 s; two 0.1 m blocks at 0.5 s x 1 fell through the floor and the containment check
// stopped the run). Now a quiet start that turned a block by more than 0.01 rad is done again from
// the given scene at steps of 0.03 sqrt(L / |g|) (L the smallest block's size): all 180 start
// within the bound (5 beyond 2 % of their tilt, by at most 1.6e-3 rad), none with a warning.
TEST(Rocking, ABlockReleasedOnItsCornerStartsWhereItWasGivenAtEveryStepSubstep) {
  const TiltedStart t = tilted_blocks_start_where_given(Integrator::Substep);
  EXPECT_EQ(t.runs, 180);
  EXPECT_EQ(t.warned, 0);
  EXPECT_TRUE(t.missed.empty()) << t.missed.size() << " missed, the first: " << t.missed.front();
}

// The warning that remains for a block the quiet start still leaves turned by more than 0.01 rad
// (quiet_start.hpp): it names the block, the turn and known limit (k), and the step that keeps a
// block of its size on its corner when the run's is longer; below 0.01 rad there is none. On
// Housner's 1 x 4.5 m block as built, its vertices turned about its pivot corner.
TEST(Rocking, AQuietStartThatLeftABlockTurnedSaysSo) {
  Scene scene = verification::rocking_block_scene();
  scene.max_step = 0.1;
  const BlockSystem given = build_block_system(scene);
  const auto turned_by = [&](double angle) {
    BlockSystem s = given;
    const Block& b = s.blocks[1];
    const Vec2 pivot = s.vertices[b.first_vertex + 1];
    for (int v = b.first_vertex; v < b.first_vertex + b.vertex_count; ++v) {
      const Vec2 d = s.vertices[v] - pivot;
      s.vertices[v] = pivot + Vec2(std::cos(angle) * d.x() - std::sin(angle) * d.y(),
                                   std::sin(angle) * d.x() + std::cos(angle) * d.y());
    }
    return quiet_start_warning(scene, s, given.vertices);
  };
  for (const double angle : {0.02, -0.05, 0.1}) {
    const std::string w = turned_by(angle);
    EXPECT_NE(w.find("block 'block' turned"), std::string::npos) << w;
    EXPECT_NE(w.find("known limits (k)"), std::string::npos) << w;
    EXPECT_NE(w.find("time.step 0.1 s is long for it"), std::string::npos) << w;
  }
  for (const double angle : {0.0, 0.005, -0.009}) EXPECT_EQ(turned_by(angle), "") << angle;
  scene.max_step = 0.005;  // under the step that keeps the block on its corner (14 ms)
  const std::string short_step = turned_by(0.02);
  EXPECT_NE(short_step.find("turned"), std::string::npos);
  EXPECT_EQ(short_step.find("is long for it"), std::string::npos) << short_step;
}

}  // namespace
}  // namespace ddafit
