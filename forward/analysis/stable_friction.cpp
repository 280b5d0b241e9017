#include "forward/analysis/stable_friction.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"

namespace ddafit {
namespace {

// Output rows often enough to see the speeds over the rest window (20 or more rows).
double trial_output_interval(const Scene& scene, const StableSearchOptions& o) {
  const double wanted = std::min(o.rest_window, o.trial_duration) / 20.0;
  return scene.output_interval > 0.0 && scene.output_interval <= wanted ? scene.output_interval : wanted;
}

// The rest criterion (stable_friction.hpp) on the run's history: per output time the
// largest speed of any measure point; its peak over the window, and its mean over each
// half (means, not peaks: a contact that chatters once in the second half is no creep).
void judge_rest(const SimulationResult& r, const StableSearchOptions& o, double rest_speed, StableTrial& t) {
  const double end = r.summary.run.simulated_time;
  const double start = end - std::min(o.rest_window, end), middle = 0.5 * (start + end);
  std::vector<std::pair<double, double>> fastest;  // (time, largest speed at that time)
  for (const HistoryRow& h : r.history) {
    if (h.time < start) continue;
    if (fastest.empty() || h.time > fastest.back().first) fastest.emplace_back(h.time, 0.0);
    fastest.back().second = std::max(fastest.back().second, h.velocity.norm());
  }
  double sum[2] = {0.0, 0.0};
  int count[2] = {0, 0};
  for (const auto& [time, speed] : fastest) {
    t.window_speed = std::max(t.window_speed, speed);
    sum[time >= middle] += speed;
    ++count[time >= middle];
  }
  t.end_speed = fastest.empty() ? 0.0 : fastest.back().second;
  const double first = count[0] ? sum[0] / count[0] : 0.0, second = count[1] ? sum[1] / count[1] : 0.0;
  t.rising = second > 1.1 * first + kRiseAllowance * rest_speed;
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
