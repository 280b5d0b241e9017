#include "forward/analysis/stable_friction.hpp"

#include <algorithm>

#include "forward/simulation.hpp"

namespace ddafit {
namespace {

// Output rows often enough to see the speeds over the rest window (20 or more rows).
double trial_output_interval(const Scene& scene, const StableSearchOptions& o) {
  const double wanted = std::min(o.rest_window, o.trial_duration) / 20.0;
  return scene.output_interval > 0.0 && scene.output_interval <= wanted ? scene.output_interval : wanted;
}

// The rest criterion (stable_friction.hpp) on the run's history.
void judge_rest(const SimulationResult& r, const StableSearchOptions& o, double rest_speed, StableTrial& t) {
  const double end = r.summary.run.simulated_time;
  const double start = end - std::min(o.rest_window, end), middle = 0.5 * (start + end);
  double first_half = 0.0, second_half = 0.0, last_time = -1.0;
  for (const HistoryRow& h : r.history) {
    if (h.time < start) continue;
    const double v = h.velocity.norm();
    double& half = h.time < middle ? first_half : second_half;
    half = std::max(half, v);
    if (h.time > last_time) {
      last_time = h.time;
      t.end_speed = 0.0;
    }
    t.end_speed = std::max(t.end_speed, v);
  }
  t.window_speed = std::max(first_half, second_half);
  t.rising = second_half > 1.1 * first_half + 0.01 * rest_speed;
  t.stable = t.window_speed < rest_speed && !t.rising;
}

StableTrial run_trial(const Scene& base, const StableSearchOptions& o, double angle) {
  Scene scene = base;
  scene.duration = o.trial_duration;
  scene.output_interval = trial_output_interval(base, o);
  scene.interfaces[o.interface].friction_angle = angle;
  // Keep the roughness share: a degraded interface stays degraded by the same fraction.
  const Interface& original = base.interfaces[o.interface];
  if (original.friction_angle > 0.0)
    scene.interfaces[o.interface].roughness_angle = original.roughness_angle * angle / original.friction_angle;
  const SimulationResult r = simulate(scene);
  StableTrial t;
  t.friction_angle = angle;
  for (const PointSummary& p : r.summary.points) t.movement = std::max(t.movement, p.max_total_displacement);
  if (r.summary.status != RunStatus::Completed) t.failure = r.summary.message;
  judge_rest(r, o, scene.rest_speed, t);
  t.stable = t.stable && t.failure.empty() && (o.max_movement <= 0.0 || t.movement <= o.max_movement);
  return t;
}

}  // namespace

StableSearchResult find_stable_friction(const Scene& scene, const StableSearchOptions& o,
                                        const std::function<void(const StableTrial&)>& on_trial) {
  StableSearchResult result;
  if (o.interface < 0 || o.interface >= static_cast<int>(scene.interfaces.size())) {
    result.message = "no such interface";
    return result;
  }
  if (scene.measure.empty()) {
    result.message = "the scene has no measure points to judge movement by";
    return result;
  }
  if (!(o.rest_window > 0.0 && o.rest_window <= o.trial_duration)) {
    result.message = "the rest window must be positive and no longer than a trial";
    return result;
  }
  auto trial = [&](double angle) {
    StableTrial t = run_trial(scene, o, angle);
    result.trials.push_back(t);
    if (on_trial) on_trial(t);
    return t.stable;
  };
  result.low = o.low;
  result.high = o.high;
  if (trial(o.low)) {
    result.message = "the scene is already stable at the low bound; lower it";
    return result;
  }
  if (!trial(o.high)) {
    result.message = "the scene still moves at the high bound; raise it";
    return result;
  }
  result.bracketed = true;
  while (result.high - result.low > o.tolerance) {
    const double mid = 0.5 * (result.low + result.high);
    (trial(mid) ? result.high : result.low) = mid;
  }
  return result;
}

}  // namespace ddafit
