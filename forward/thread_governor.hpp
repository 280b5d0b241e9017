// How many threads the substep solver's loops use, chosen step by step while the run goes.
// A run's numbers do not depend on it (docs/theory.md §13, "Threads"): only its wall time does.
#pragma once

#include <functional>
#include <vector>

namespace ddafit {

// Two threads pay only where a step has enough contacts to share and the second core is free.
// On Vajont section I degraded (183 blocks, substep) one thread was the faster alone (8.9 s
// against 9.7-11.4 s on two), and two runs of it started together on two threads each took
// 126 s apiece, 12x their solo wall: at every loop's barrier each thread waited for one that
// the other run had displaced from its core. The governor therefore times windows of steps on
// one thread and on all the run may use, in turn, and takes the faster for the steps that
// follow; then it times them again, since the machine's load changes. The windows are compared
// by their median step: an impact group solved in one step (on one thread, whatever the count)
// makes that step several times dearer, and two or three such steps in a window of 16 made
// its sum say nothing of the thread count (section VII degraded ran 26-29 % of its steps on one
// thread by sums, 15 % by medians, of which 6 % are the windows on one thread themselves).
struct ThreadGovernorSettings {
  int window_steps = 16;  // steps per timed window
  int hold_steps = 240;   // steps on the chosen count before timing again
  // One thread is kept unless all of them take at least this share less time per step: the
  // second core is then left to whatever else the machine runs.
  double margin = 0.05;
  // All threads slower than one by this factor is a clear loss: another program holds the
  // other core. Each clear loss in a row doubles the hold, up to max_hold_steps, so that the
  // windows on all threads, each of whose barriers then waits for a displaced thread, are timed
  // less and less often. Two Vajont section I runs at once spent 304 of their 5003 steps in such
  // windows at a fixed hold, about a third of their wall (docs/performance.md, "Two runs at
  // once, again"). A mild loss (a scene too small to share) keeps hold_steps.
  double clear_loss = 1.5;
  int max_hold_steps = 1920;
  // All threads faster than one by this factor is a clear win, and each clear win in a row
  // doubles the hold as well, up to max_hold_steps: the windows on one thread are then a
  // growing share of nothing. On Vajont section VII degraded two threads ran a step 1.4-2.1x
  // faster than one in most pairs of windows (1.1-1.2x in two of eleven), and at a fixed hold
  // 16 of every 272 steps ran on one thread; with doubled holds 64-96 of its 5254 steps did, and
  // the run took 107.0 s against 113.9 s (means of three, docs/performance.md).
  double clear_win = 1.25;
  // A long hold on all threads ends early once slow_steps steps in a row each take more than
  // slow_factor times the window's median on all threads: another program has taken a core, and
  // the run re-times rather than waiting at every barrier for the rest of the hold. A dear step
  // or two (an impact group) is no run of them.
  double slow_factor = 2.0;
  int slow_steps = 8;
  // A window on all threads ends after cut_steps steps once their median is a clear loss
  // against the one-thread median (this pair's, or the last pair's when all threads go first).
  // Each such step waits at every barrier for a thread another program displaced, ten or more
  // times a step on one thread: two Vajont section I runs started together at 20 ms x 4 (2571
  // steps, 2.9 s alone) spent 2.2 s of their quiet start's 500 steps so (0.46 s alone), and took
  // 2.2-2.8x their solo wall (docs/performance.md, "Two runs at once at 20 ms x 4").
  int cut_steps = 4;
};

// The threads a run may use: OpenMP's present maximum (set from --threads), 1 without OpenMP.
int threads_allowed();

class ThreadGovernor {
 public:
  // `most`: the threads the run may use (its --threads, or OpenMP's default). `clock`: seconds,
  // monotonic (the wall clock; a test passes its own).
  explicit ThreadGovernor(int most, ThreadGovernorSettings settings = {}, std::function<double()> clock = {});
  // Restores OpenMP's thread count as it found it, for whatever runs after the run.
  ~ThreadGovernor();
  ThreadGovernor(const ThreadGovernor&) = delete;
  ThreadGovernor& operator=(const ThreadGovernor&) = delete;

  // Before a step: sets and returns the thread count the step is to use.
  int begin_step();
  // After it: the step's wall time counts towards the window it ran in.
  void end_step();
  // Steps run on one thread / on `most` so far.
  long steps_on_one() const { return steps_on_one_; }
  long steps_on_most() const { return steps_on_most_; }

 private:
  enum class Phase { First, Second, Hold };
  int most_;
  int found_;  // OpenMP's thread count when the governor was made
  ThreadGovernorSettings settings_;
  std::function<double()> clock_;
  Phase phase_ = Phase::First;
  // Which count the next pair of windows times first. One thread first in the first pair, so that
  // its window on all threads has a median to be cut against (ThreadGovernorSettings::cut_steps).
  bool most_first_ = false;
  int current_ = 1;
  int steps_in_phase_ = 0;
  int hold_ = 0;                    // steps of the present hold
  bool clear_loss_before_ = false;  // the last pair of windows was a clear loss
  bool clear_win_before_ = false;   // ... a clear win
  double most_median_ = 0.0;        // the last pair's median step on all threads
  double one_median_ = 0.0;         // ... on one thread (0 before the first pair)
  int slow_in_row_ = 0;             // steps in a row of the hold beyond slow_factor x most_median_
  double started_ = 0.0;
  std::vector<double> seconds_[2];  // each step's wall in the pair's windows: [0] one thread, [1] most
  long steps_on_one_ = 0, steps_on_most_ = 0;
  void set_threads(int threads);
  bool clear_loss_so_far();
};

}  // namespace ddafit
