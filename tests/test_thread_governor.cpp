// The thread governor (forward/thread_governor.hpp): it times windows of steps on one thread
// and on all the run may use, and keeps the faster. Driven here by a clock of the test's own,
// with a cost per step that depends on the thread count, so the choice is known exactly.
#include <gtest/gtest.h>

#include <functional>

#include "forward/thread_governor.hpp"

namespace ddafit {
namespace {

struct Steps {
  double now = 0.0;
  long on_one = 0, on_most = 0;
};

// Runs `count` steps; a step on one thread costs cost(1), on more cost(threads).
void run_steps(ThreadGovernor& governor, Steps& clock, int count, const std::function<double(int)>& cost) {
  for (int k = 0; k < count; ++k) {
    const int threads = governor.begin_step();
    clock.now += cost(threads);
    governor.end_step();
  }
}

ThreadGovernor make(int most, Steps& clock) {
  return ThreadGovernor(most, ThreadGovernorSettings{}, [&clock] { return clock.now; });
}

// Steps twice as fast on two threads, but every eighth (an impact group, solved on one thread
// whatever the count) ten times dearer on two.
std::function<double(int)> dear_every_eighth() {
  return [step = 0](int t) mutable {
    const bool impact = (step++ % 8) == 3;
    return t == 1 ? 1.0 : (impact ? 10.0 : 0.5);
  };
}

// Over 5003 steps (Vajont section I's count) where a step costs 1 on one thread and `on_two` on
// two: the steps spent timing the count the governor does not keep (its windows on it).
long steps_timing_the_other(double on_two) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, 5003, [on_two](int t) { return t == 1 ? 1.0 : on_two; });
  return on_two < 1.0 ? governor.steps_on_one() : governor.steps_on_most();
}

// Two windows of 16 steps, then 240 on the choice: the first choice holds from step 32 to 271. A
// window on two threads that is a clear loss ends after kCut steps (ThreadGovernorSettings::cut_steps).
constexpr int kWindow = 16;
constexpr int kCut = 4;
constexpr int kPair = 2 * kWindow;
constexpr int kHold = 240;

// A step twice as fast on two threads: after the first pair of windows every step is on two.
TEST(ThreadGovernor, KeepsAllThreadsWhereTheyAreFaster) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, kPair, [](int t) { return t == 1 ? 1.0 : 0.5; });
  const long one_before = governor.steps_on_one();
  EXPECT_EQ(one_before, kWindow);  // the trial's window on one thread
  run_steps(governor, clock, kHold, [](int t) { return t == 1 ? 1.0 : 0.5; });
  EXPECT_EQ(governor.steps_on_one(), one_before);
}

// Two threads slower (the other core is busy, or the scene too small to share): one thread.
TEST(ThreadGovernor, FallsBackToOneThreadWhereItIsFaster) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, kPair + kHold, [](int t) { return t == 1 ? 1.0 : 1.2; });
  EXPECT_EQ(governor.steps_on_most(), kWindow);
  EXPECT_EQ(governor.steps_on_one(), kPair + kHold - kWindow);
}

// Within the margin (5 %) one thread is kept: the second core is left to the machine.
TEST(ThreadGovernor, KeepsOneThreadWhenTwoGainLessThanTheMargin) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, kPair + kHold, [](int t) { return t == 1 ? 1.0 : 0.97; });
  EXPECT_EQ(governor.steps_on_most(), kWindow);
}

// The machine's load changes: two threads pay at first, then another program takes the second
// core and they do not. The next pair of windows sees it and the run drops to one thread.
TEST(ThreadGovernor, TimesAgainAndFollowsTheMachine) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, kPair + kHold, [](int t) { return t == 1 ? 1.0 : 0.5; });
  const long most_before = governor.steps_on_most();
  EXPECT_EQ(most_before, kPair + kHold - kWindow);
  // The next pair times two threads first (the order alternates), and cuts that window short
  // after kCut steps, a clear loss against the last pair's one-thread step; then it holds on one.
  run_steps(governor, clock, kPair + kHold, [](int t) { return t == 1 ? 1.0 : 3.0; });
  EXPECT_EQ(governor.steps_on_most() - most_before, kCut);
}

// A few dear steps (an impact group, solved on one thread whatever the count) in the window on
// two threads do not decide: windows are compared by their median step. By their sums, two
// steps of 10 s among fourteen of 0.5 s (27 s) would lose to sixteen of 1 s.
TEST(ThreadGovernor, ADearStepOrTwoDoNotDecide) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, kPair + kHold, dear_every_eighth());
  EXPECT_EQ(governor.steps_on_one(), kWindow);
}

// Another program holds the other core for the whole run (two Vajont section I runs at once:
// a step on two threads took about ten times one on one). Each clear loss in a row doubles the
// hold (240, 480, 960, 1920, 1920 steps), so over section I's 5003 steps the windows on two
// threads are five, not the nineteen of a fixed hold (304 steps); and each ends after kCut
// steps, once their median is a clear loss: 20 steps at ten times the cost, not 80.
TEST(ThreadGovernor, APersistentClearLossIsTimedLessAndLessOften) {
  EXPECT_EQ(steps_timing_the_other(10.0), 5 * kCut);
}

// A mild loss (a scene too small to share: section I alone, two threads 10-25 % slower) keeps
// the fixed hold, so the run finds two threads again within 272 steps once they pay.
TEST(ThreadGovernor, AMildLossKeepsTheFixedHold) {
  EXPECT_EQ(steps_timing_the_other(1.2), 19 * kWindow);  // a pair every 272 steps: 19 begin before 5003
}

// When the other program ends, the next pair of windows sees two threads win and the hold is
// the fixed one again: after clear losses the run is back on two threads at the next timing.
TEST(ThreadGovernor, TheBackOffEndsWhenTwoThreadsWinAgain) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  // Four pairs, each a window of 16 on one thread and one of kCut on two, and holds of 240, 480
  // and 960: a hold of 1920 begins at step 1760.
  run_steps(governor, clock, 1760, [](int t) { return t == 1 ? 1.0 : 10.0; });
  run_steps(governor, clock, 1920, [](int t) { return t == 1 ? 1.0 : 0.5; });  // the hold runs out on one thread
  const long most_before = governor.steps_on_most();
  EXPECT_EQ(most_before, 4 * kCut);
  run_steps(governor, clock, kPair + kHold, [](int t) { return t == 1 ? 1.0 : 0.5; });
  EXPECT_EQ(governor.steps_on_most() - most_before, kWindow + kHold);  // its window on two, then the hold
  // A clear loss (its window on two cut short) now holds 240 steps, not twice the last hold.
  run_steps(governor, clock, kCut + kWindow + kHold, [](int t) { return t == 1 ? 1.0 : 10.0; });
  const long one_before = governor.steps_on_one();
  run_steps(governor, clock, kPair, [](int t) { return t == 1 ? 1.0 : 0.5; });
  EXPECT_EQ(governor.steps_on_one() - one_before, kWindow);
}

// Two threads a clear win (on Vajont section VII degraded a step ran 1.4-2.1x faster on two in
// nine of eleven pairs of windows): each clear win in a row doubles the hold (240, 480, 960,
// 1920, 1920), so over 5003 steps five windows run on one thread, not nineteen.
TEST(ThreadGovernor, ClearWinsInARowAreTimedLessAndLessOften) {
  EXPECT_EQ(steps_timing_the_other(0.5), 5 * kWindow);
}

// A mild win (two threads 10 % faster, under the clear win's 1.25) keeps the fixed hold: the
// choice is close, and is timed again every 272 steps.
TEST(ThreadGovernor, AMildWinKeepsTheFixedHold) {
  EXPECT_EQ(steps_timing_the_other(0.9), 19 * kWindow);
}

// Another program takes the second core in the middle of a long hold on two threads: the run
// does not wait at its barriers for the rest of the hold (1920 steps) but re-times after eight
// slow steps in a row, and moves to one thread after the pair of windows.
TEST(ThreadGovernor, ALoadArrivingInALongHoldEndsItWithinEightSteps) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, 1808, [](int t) { return t == 1 ? 1.0 : 0.5; });  // four pairs; a hold of 1920 begins
  const long most_before = governor.steps_on_most();
  run_steps(governor, clock, 200, [](int t) { return t == 1 ? 1.0 : 10.0; });
  // Eight slow steps of the hold, then the pair's window on one thread (the order alternates:
  // four pairs so far), then its window on two, cut short after kCut steps, and the hold on one.
  EXPECT_EQ(governor.steps_on_most() - most_before, 8 + kCut);
}

// Dear steps scattered through a long hold (an impact group every eighth step, ten times a
// plain step) are no run of slow steps: the holds still double.
TEST(ThreadGovernor, DearStepsInALongHoldDoNotEndIt) {
  Steps clock;
  ThreadGovernor governor = make(2, clock);
  run_steps(governor, clock, 5003, dear_every_eighth());
  EXPECT_EQ(governor.steps_on_one(), 5 * kWindow);
}

// A run allowed one thread never changes it.
TEST(ThreadGovernor, OneThreadAllowedIsOneThreadUsed) {
  Steps clock;
  ThreadGovernor governor = make(1, clock);
  run_steps(governor, clock, 500, [](int t) { return t == 1 ? 1.0 : 0.1; });
  EXPECT_EQ(governor.steps_on_one(), 500);
  EXPECT_EQ(governor.steps_on_most(), 0);
}

}  // namespace
}  // namespace ddafit
