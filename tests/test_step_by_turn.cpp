// control.step_by_turn (options.hpp): a block in contact shortens the substep solver's step
// only by the travel its turning gives its vertices; one that slides further than the move limit
// in a step widens its contacts' margin instead (speculative contact). The class it must still
// get right is the commonest event of a jointed slide at landslide speed: a slider across flush
// joints at 10 and 30 m/s, at steps of 10 and 20 ms (0.1-0.6 m a step, up to several times the
// move limit). Slopes that speed it up (28/18, 20/12, 35/33 deg) and one that slows it (10 deg at
// 20 deg friction), sliders of 0.5-3 m over joints every 0.3 and 2.5 m, each descending to the
// right and to the left (forward/mirror.hpp): 192 runs, each within test_joint_crossing.cpp's
// tolerance, 1 % of seed Eq. 4 wherever the slider has moved 1 cm, and under the energy audit
// and 1 % overlap of contact_scene_audit.hpp.
#include <iostream>
#include <string>

#include "tests/contact_scene_audit.hpp"
#include "tests/slope_scene.hpp"

namespace ddafit {
namespace {

struct CrossingRun {
  SimulationResult result;
  std::string label;
};

CrossingRun run_crossing(const Crossing& c, double step, bool mirrored, bool by_turn) {
  Scene scene = crossing_scene(c, Integrator::Substep);
  scene.max_step = step;
  scene.output_interval = step;
  scene.options.step_by_turn = by_turn;
  if (mirrored) scene = mirrored_scene(scene);
  RunAudit audit;
  CrossingRun run{simulate(scene, audit_hooks(audit, scene.gravity)),
               describe(c, Integrator::Substep) + ", step " + std::to_string(step) + " s" +
                   (mirrored ? ", descending to the left" : "") +
                   (by_turn ? ", step by turn" : "")};
  if (mirrored) unmirror_history(run.result.history);
  expect_contact_physics(run.result, audit, Integrator::Substep, run.label);
  return run;
}

// The steps a run of `duration` takes at the scene's `step` (outputs fall on steps: run_crossing).
double steps_of_the_scene(double duration, double step) { return std::ceil(duration / step - 1e-9); }

TEST(StepByTurn, FastSlidersFollowSeedEq4) {
  double worst = 0.0;
  std::string worst_label;
  const int runs = for_each_fast_slider({0.01, 0.02}, [&](const Crossing& c, double step, bool mirrored) {
    const CrossingRun run = run_crossing(c, step, mirrored, true);
    const SimulationResult& r = run.result;
    ASSERT_EQ(r.summary.status, RunStatus::Completed) << run.label << ": " << r.summary.message;
    // The contract: the slider's speed along the slope no longer shortens the step (the last
    // step may land on the run's end).
    EXPECT_LE(r.summary.run.steps, steps_of_the_scene(kDuration, step)) << run.label;
    double when = 0.0;
    const double error = displacement_error(r, c, &when);
    EXPECT_LT(error, kDisplacementTolerance) << run.label << ": worst at t = " << when << " s";
    if (error > worst) worst = error, worst_label = run.label;
  });
  EXPECT_EQ(runs, 192);
  std::cout << "[measured] " << runs << " sliders at 10 and 30 m/s, 10 and 20 ms, step by turn: worst "
            << "displacement error " << worst << " (" << worst_label << ")\n";
}

// By the whole travel (the default) the same fast slider does shorten the step: the setting is
// what lets it through, not a scene whose move limit was loose anyway. A 0.5 m slider's move limit
// is half its width, 0.25 m (block_system.hpp), and at 30 m/s a 20 ms step carries it 0.6 m.
TEST(StepByTurn, TheWholeTravelShortensTheStepOfAFastSlider) {
  Crossing c;
  c.slope = 28.0, c.friction = 18.0, c.length = 0.5, c.height = 0.5, c.spacing = 0.3, c.speed = 30.0;
  const CrossingRun whole = run_crossing(c, 0.02, false, false);
  const CrossingRun by_turn = run_crossing(c, 0.02, false, true);
  ASSERT_EQ(whole.result.summary.status, RunStatus::Completed) << whole.result.summary.message;
  ASSERT_EQ(by_turn.result.summary.status, RunStatus::Completed) << by_turn.result.summary.message;
  EXPECT_LT(whole.result.summary.run.smallest_step, 0.5 * 0.02) << whole.label;
  EXPECT_GT(whole.result.summary.run.steps, 2.0 * steps_of_the_scene(kDuration, 0.02)) << whole.label;
  EXPECT_NEAR(by_turn.result.summary.run.smallest_step, 0.02, 1e-12) << by_turn.label;
}

}  // namespace
}  // namespace ddafit
