// The friction angle at which a scene stays put (the seed's "stable state", §3.4b):
// bisection on one interface's peak friction angle, each trial a forward run.
//
// A trial is stable when its motion has died out: over the last `rest_window` seconds of
// the trial the largest speed of any measure point stays below the scene's rest_speed, and
// it is not rising (its mean over the window's second half is not above its mean over the
// first half by more than 10 % plus kRiseAllowance x rest_speed). Elastic settling of a thick mass is
// then not sliding, and slow creep, below rest_speed but accelerating, is not rest. A
// largest displacement (`max_movement`) is an optional extra condition.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

// The absolute part of "rising", as a share of rest_speed: above the noise of a mass at rest
// (Vajont section VII at 27 deg, substep solver, 20 s: the fastest point's half-second means
// wander between 0.002 and 0.005 m/s; 1 % of rest_speed read 2 of 17 windows as rising,
// 5 % none), below the rise of a real creep (a block 0.1 deg under its friction angle gains
// 0.009 m/s over the window's second half).
constexpr double kRiseAllowance = 0.05;

struct StableSearchOptions {
  int interface = -1;          // index into Scene::interfaces whose friction angle is searched
  double low = 5.0;            // deg, expected to slide
  double high = 45.0;          // deg, expected to stay put
  double tolerance = 0.5;      // deg: stop when high - low is below this
  // s simulated per trial. Vajont section I at 22 deg, 10 s: the fastest point moves at
  // 0.001 m/s over the last second on the substep solver, 0.066 m/s on the implicit one (its
  // 250 m thick elastic mass still rings), both under rest_speed (docs/vajont.md).
  double trial_duration = 10.0;
  double rest_window = 1.0;    // s at the end of a trial over which the speeds are judged
  double max_movement = 0.0;   // m; > 0 adds "no measure point moved further" to the criterion
};

struct StableTrial {
  double friction_angle = 0.0;
  double movement = 0.0;     // largest max_total_displacement over the measure points, m
  double window_speed = 0.0; // largest speed of any measure point over the rest window, m/s
  double end_speed = 0.0;    // largest speed of any measure point at the trial's end, m/s
  bool rising = false;       // the speeds grew over the rest window
  bool stable = false;
  std::string failure;       // the run's diagnosis if it failed (counted as not stable)
};

struct StableSearchResult {
  bool bracketed = false;  // low slid and high stayed
  double low = 0.0, high = 0.0;  // final bracket, deg
  std::vector<StableTrial> trials;
  std::string message;
};

StableSearchResult find_stable_friction(const Scene& scene, const StableSearchOptions& options,
                                        const std::function<void(const StableTrial&)>& on_trial = {});

}  // namespace ddafit
