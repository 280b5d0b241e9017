// The bounding friction: chi^2 along the degradation parameter and the values of mu_b
// where it stays within 1 and 4 of its minimum. With as many observations as parameters
// a linearised interval means little (FIELD_NOTES, back-analysis); the profile does not
// rely on linearity and respects the bounds.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "inverse/forward_call.hpp"
#include "inverse/inversion.hpp"

namespace ddafit::inverse {

namespace {

// Walks from the minimum to each side until chi^2 rises above min + threshold and
// interpolates between the last point inside and the first outside, linearly in
// sqrt(Delta chi^2): near a minimum chi^2 is quadratic, so sqrt(Delta) is linear in the
// distance from it, and the crossing is exact even across a bracket wider than the range.
ProfileRange range_of(const std::vector<ProfilePoint>& pts, size_t at_min, double chi2_min, double threshold) {
  ProfileRange r;
  r.threshold = threshold;
  const double level = chi2_min + threshold;
  const auto cross = [&](size_t in, size_t out) {
    const double a = std::sqrt(std::max(0.0, pts[in].chi2 - chi2_min)), b = std::sqrt(pts[out].chi2 - chi2_min);
    const double t = (std::sqrt(threshold) - a) / (b - a);
    return pts[in].value + t * (pts[out].value - pts[in].value);
  };
  size_t k = at_min;
  while (k > 0 && pts[k - 1].chi2 <= level) --k;
  r.low_at_bound = k == 0;
  r.low = k == 0 ? pts.front().value : cross(k, k - 1);
  k = at_min;
  while (k + 1 < pts.size() && pts[k + 1].chi2 <= level) ++k;
  r.high_at_bound = k + 1 == pts.size();
  r.high = k + 1 == pts.size() ? pts.back().value : cross(k, k + 1);
  return r;
}

std::vector<ProfilePoint> completed(const std::vector<ProfilePoint>& profile) {
  std::vector<ProfilePoint> good;
  std::copy_if(profile.begin(), profile.end(), std::back_inserter(good), [](const ProfilePoint& q) { return !q.failed; });
  return good;
}

size_t index_of_min(const std::vector<ProfilePoint>& pts) {
  size_t at_min = 0;
  for (size_t k = 1; k < pts.size(); ++k)
    if (pts[k].chi2 < pts[at_min].chi2) at_min = k;
  return at_min;
}

}  // namespace

ProfileRange profile_range(const std::vector<ProfilePoint>& profile, double threshold) {
  const std::vector<ProfilePoint> good = completed(profile);
  if (good.empty()) return {};
  const size_t at_min = index_of_min(good);
  return range_of(good, at_min, good[at_min].chi2, threshold);
}

BoundingFriction profile_friction(Objective& objective, const Study& study, const std::vector<double>& best,
                                  int parameter, int points, bool reoptimize, int budget, const ProfileScore& score) {
  const ProfileScore scored = score ? score : [&](const std::vector<double>& x) { return objective.evaluate(x); };
  BoundingFriction f;
  const Parameter& p = study.parameters.at(parameter);
  f.parameter = parameter;
  f.reoptimized = reoptimize;
  f.best_value = best[parameter];
  const std::string rest = p.key.substr(std::string("interfaces.").size());
  f.interface = rest.substr(0, rest.find('.'));
  f.peak_angle = objective.scene().peak_friction_angle(best, p.key);
  if (!std::isfinite(f.peak_angle)) {
    f.why_not = "the scene has no interface '" + f.interface + "' with a friction angle";
    return f;
  }
  f.available = true;
  f.mu_best = residual_friction(study, parameter, f.peak_angle, f.best_value);

  std::vector<bool> others;
  for (size_t j = 0; j < study.parameters.size(); ++j)
    others.push_back(!study.parameters[j].discrete() && static_cast<int>(j) != parameter);
  const bool any_other = std::find(others.begin(), others.end(), true) != others.end();
  const auto add_point = [&](double value) {
    for (const ProfilePoint& q : f.profile)
      if (q.value == value) return;
    std::vector<double> x = best;
    x[parameter] = value;
    ProfilePoint pt;
    pt.value = value;
    if (reoptimize && any_other && value != f.best_value) {
      const FitResult r = fit(objective, study, x, others, budget);
      pt.values = r.best;
      pt.chi2 = r.chi2;
    } else {
      pt.values = x;
      pt.chi2 = scored(x).chi2;
    }
    pt.failed = pt.chi2 >= kFailedMisfit;
    pt.chi2_observations = chi2_observations_only(study, scored(pt.values));  // from the log: no run
    pt.mu = residual_friction(study, parameter, f.peak_angle, value);
    const auto at = std::lower_bound(f.profile.begin(), f.profile.end(), value,
                                     [](const ProfilePoint& a, double v) { return a.value < v; });
    f.profile.insert(at, pt);
  };
  // The grid's runs are independent when the other parameters stay at the best fit: they
  // run as one batch (--jobs at a time); add_point then finds each in the objective's log.
  if (!reoptimize || !any_other) {
    std::vector<std::vector<double>> grid;
    for (int k = 0; k < points; ++k) {
      grid.push_back(best);
      grid.back()[parameter] = p.lower + (p.upper - p.lower) * k / (points - 1);
    }
    objective.evaluate_batch(grid, objective.jobs);
  }
  for (int k = 0; k < points; ++k) add_point(p.lower + (p.upper - p.lower) * k / (points - 1));
  add_point(f.best_value);

  // Bisect each crossing of Delta chi^2 = 1 and 4 down to one resolution, so the range
  // does not depend on the scan spacing (about log2(spacing / resolution) runs each).
  // A failed run says nothing about the fit there, so it neither ends a range nor marks a
  // crossing: the ranges are read off the runs that completed (on the Vajont profile one
  // failure at 57 % had cut the Delta chi^2 <= 4 range off at 56 % although 58-60 % fit).
  for (int extra = 0; extra < 48; ++extra) {
    const std::vector<ProfilePoint> good = completed(f.profile);
    if (good.empty()) break;
    const double chi2_min = good[index_of_min(good)].chi2;
    f.delta1 = profile_range(f.profile, 1.0);
    f.delta4 = profile_range(f.profile, 4.0);
    double split = NAN;
    for (size_t k = 0; k + 1 < good.size() && std::isnan(split); ++k) {
      const ProfilePoint &a = good[k], &b = good[k + 1];
      const bool crosses = (a.chi2 - chi2_min <= 1.0) != (b.chi2 - chi2_min <= 1.0) ||
                           (a.chi2 - chi2_min <= 4.0) != (b.chi2 - chi2_min <= 4.0);
      if (!crosses || b.value - a.value <= 1.5 * p.resolution) continue;
      // The midpoint on the resolution grid, or the nearest free grid value when a failed
      // run already holds it (else the bisection would ask for that run again and again).
      const double mid = a.value + std::round(0.5 * (b.value - a.value) / p.resolution) * p.resolution;
      for (int step = 0; step < 64 && std::isnan(split); ++step) {
        for (const double candidate : {mid - step * p.resolution, mid + step * p.resolution}) {
          const bool inside = candidate > a.value + 0.5 * p.resolution && candidate < b.value - 0.5 * p.resolution;
          const bool taken = std::any_of(f.profile.begin(), f.profile.end(), [&](const ProfilePoint& q) {
            return std::abs(q.value - candidate) < 0.5 * p.resolution;
          });
          if (inside && !taken) {
            split = candidate;
            break;
          }
        }
      }
    }
    if (std::isnan(split)) break;
    add_point(split);
  }
  f.with_model_sigma = study.has_model_sigma();
  if (f.with_model_sigma) {
    std::vector<ProfilePoint> observations_only = f.profile;
    for (ProfilePoint& q : observations_only) q.chi2 = q.chi2_observations;
    f.delta1_observations = profile_range(observations_only, 1.0);
    f.delta4_observations = profile_range(observations_only, 4.0);
  }
  for (ProfileRange* r : {&f.delta1, &f.delta4, &f.delta1_observations, &f.delta4_observations}) {
    // mu falls as degradation (or roughness) rises: the low mu belongs to the high value.
    r->mu_low = residual_friction(study, parameter, f.peak_angle, r->high);
    r->mu_high = residual_friction(study, parameter, f.peak_angle, r->low);
  }
  return f;
}

}  // namespace ddafit::inverse
