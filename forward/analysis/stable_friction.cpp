#include "forward/analysis/stable_friction.hpp"

#include <algorithm>

#include "forward/simulation.hpp"

namespace ddafit {
namespace {

StableTrial run_trial(const Scene& base, const StableSearchOptions& o, double angle) {
  Scene scene = base;
  scene.duration = o.trial_duration;
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
  t.stable = t.failure.empty() && t.movement <= o.max_movement;
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
