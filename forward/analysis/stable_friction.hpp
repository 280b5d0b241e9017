// The friction angle at which a scene stays put (the seed's "stable state", §3.4b):
// bisection on one interface's peak friction angle, each trial a forward run.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

struct StableSearchOptions {
  int interface = -1;          // index into Scene::interfaces whose friction angle is searched
  double low = 5.0;            // deg, expected to slide
  double high = 45.0;          // deg, expected to stay put
  double tolerance = 0.5;      // deg: stop when high - low is below this
  double trial_duration = 5.0; // s simulated per trial
  double max_movement = 0.1;   // m: a trial is stable when no measure point moves further
};

struct StableTrial {
  double friction_angle = 0.0;
  double movement = 0.0;  // largest max_total_displacement over the measure points, m
  bool stable = false;
  std::string failure;    // the run's diagnosis if it failed (counted as not stable)
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
