// The substep solver's promise that 1 and 2 threads give the same numbers bit for bit.
#include <gtest/gtest.h>

#include "forward/geometry.hpp"
#include "forward/simulation.hpp"
#include "tests/threads_agree.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

Vec2 centroid_of(const std::vector<Vec2>& polygon) { return polygon_moments(polygon).centroid; }

// --- 6. Thread determinism of the substep solver --------------------------------------

// A loop runs on several threads only from kParallelMinimum (512) items up; the contact
// sweeps run colour by colour, each colour of 64 manifolds or more on both threads in
// static shares (solve_contacts.cpp; 512 before model revision 2026-11-27.2). The
// 20 x 30 wall (600 bricks, 1731 manifolds) has six colours of 261-315 manifolds, which the
// old threshold kept on one thread, so this test takes a larger wall. This 40 x 30 wall
// (1200 bricks, 3491 manifolds at t = 0) has six colours of 551-615, so every loop of the
// step runs on both threads; the quiet start, which takes most of the run time, runs the
// same sweeps and is compared through the rows of t = 0. The thread governor
// (forward/thread_governor.hpp) may then run steps on one thread where that is faster, but
// it times every pair of windows on both threads as well, starting with the quiet start's
// first 16 steps, so both counts are in the two-thread run. The graph colouring makes the
// order of every floating-point operation independent of the thread count: the histories
// must agree bit for bit, not within a tolerance.
TEST(SubstepScenesThreads, OneAndTwoThreadsAgreeBitForBit) {
  Scene one = verification::brick_wall_scene(40, 30, 0.05);
  one.options.integrator = Integrator::Substep;
  // Every brick's centre is measured, not only the top one: 1200 points x 6 output times.
  for (const BlockInput& b : one.blocks)
    if (!b.fixed) one.measure.push_back({b.name, centroid_of(b.polygon)});
  expect_same_on_one_and_two_threads(one, "40 x 30 wall");
}

}  // namespace
}  // namespace ddafit
