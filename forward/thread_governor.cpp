#include "forward/thread_governor.hpp"

#include <algorithm>
#include <chrono>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ddafit {
namespace {

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double median(std::vector<double>& values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

int threads_allowed() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

ThreadGovernor::ThreadGovernor(int most, ThreadGovernorSettings settings, std::function<double()> clock)
    : most_(most < 1 ? 1 : most), found_(threads_allowed()), settings_(settings), clock_(clock ? std::move(clock) : wall_seconds) {
  current_ = most_;
}

ThreadGovernor::~ThreadGovernor() {
  if (most_ > 1) set_threads(found_);
}

void ThreadGovernor::set_threads(int threads) {
  current_ = threads;
#ifdef _OPENMP
  omp_set_num_threads(threads);
#endif
}

int ThreadGovernor::begin_step() {
  if (most_ > 1) {
    // The pair's first window on one count, its second on the other; the order alternates from
    // pair to pair, so that a run growing steadily dearer favours neither.
    if (phase_ == Phase::First) set_threads(most_first_ ? most_ : 1);
    if (phase_ == Phase::Second) set_threads(most_first_ ? 1 : most_);
  }
  started_ = clock_();
  return current_;
}

void ThreadGovernor::end_step() {
  (current_ == 1 ? steps_on_one_ : steps_on_most_) += 1;
  if (most_ == 1) return;
  const double seconds = clock_() - started_;
  ++steps_in_phase_;
  if (phase_ == Phase::Hold) {
    if (current_ == most_) {
      slow_in_row_ = seconds > settings_.slow_factor * most_median_ ? slow_in_row_ + 1 : 0;
      if (slow_in_row_ >= settings_.slow_steps) clear_win_before_ = false, hold_ = 0;  // re-time now
    }
    if (steps_in_phase_ >= hold_) phase_ = Phase::First, steps_in_phase_ = 0;
    return;
  }
  seconds_[current_ == 1 ? 0 : 1].push_back(seconds);
  if (steps_in_phase_ < settings_.window_steps && !clear_loss_so_far()) return;
  steps_in_phase_ = 0;
  if (phase_ == Phase::First) {
    phase_ = Phase::Second;
    return;
  }
  const double one = median(seconds_[0]), all = median(seconds_[1]);
  set_threads(all < (1.0 - settings_.margin) * one ? most_ : 1);
  const bool clear_loss = all > settings_.clear_loss * one, clear_win = one > settings_.clear_win * all;
  const bool in_a_row = (clear_loss && clear_loss_before_) || (clear_win && clear_win_before_);
  hold_ = in_a_row ? std::min(2 * hold_, settings_.max_hold_steps) : settings_.hold_steps;
  clear_loss_before_ = clear_loss;
  clear_win_before_ = clear_win;
  most_median_ = all;
  one_median_ = one;
  slow_in_row_ = 0;
  seconds_[0].clear();
  seconds_[1].clear();
  most_first_ = !most_first_;
  phase_ = Phase::Hold;
}

bool ThreadGovernor::clear_loss_so_far() {
  if (current_ == 1 || steps_in_phase_ < settings_.cut_steps) return false;
  // median() reorders in place; a window's order means nothing, so no copy is needed.
  const double one = seconds_[0].empty() ? one_median_ : median(seconds_[0]);
  return one > 0.0 && median(seconds_[1]) > settings_.clear_loss * one;
}

}  // namespace ddafit
