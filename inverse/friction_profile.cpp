// The bounding friction: chi^2 along the degradation parameter and the values of mu_b
// where it stays within 1 and 4 of its minimum. With as many observations as parameters
// a linearised interval means little (FIELD_NOTES, back-analysis); the profile does not
// rely on linearity and respects the bounds.
#include <algorithm>
#include <cmath>

#include "inverse/forward_call.hpp"
#include "inverse/inversion.hpp"

namespace ddafit::inverse {

namespace {

// Walks from the minimum to each side until chi^2 rises above min + threshold and
// interpolates linearly between the last point inside and the first outside.
ProfileRange range_of(const std::vector<ProfilePoint>& pts, size_t at_min, double chi2_min, double threshold) {
  ProfileRange r;
  r.threshold = threshold;
  const double level = chi2_min + threshold;
  const auto cross = [&](size_t in, size_t out) {
    const double t = (level - pts[in].chi2) / (pts[out].chi2 - pts[in].chi2);
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

}  // namespace

BoundingFriction profile_friction(Objective& objective, const Study& study, const std::vector<double>& best,
                                  int parameter, int points, bool reoptimize, int budget) {
  BoundingFriction f;
  const Parameter& p = study.parameters.at(parameter);
  f.parameter = parameter;
  f.reoptimized = reoptimize;
  f.best_value = best[parameter];
  const std::string rest = p.key.substr(std::string("interfaces.").size());
  f.interface = rest.substr(0, rest.find('.'));
  f.peak_angle = peak_friction_angle(study, best, p.key);
  if (!std::isfinite(f.peak_angle)) {
    f.why_not = "the scene has no interface '" + f.interface + "' with a friction angle";
    return f;
  }
  f.available = true;
  f.mu_best = residual_friction(study, parameter, f.peak_angle, f.best_value);

  std::vector<double> scan;
  for (int k = 0; k < points; ++k) scan.push_back(p.lower + (p.upper - p.lower) * k / (points - 1));
  scan.push_back(f.best_value);
  std::vector<bool> others;
  for (size_t j = 0; j < study.parameters.size(); ++j)
    others.push_back(!study.parameters[j].discrete() && static_cast<int>(j) != parameter);
  const bool any_other = std::find(others.begin(), others.end(), true) != others.end();
  for (double value : scan) {
    std::vector<double> x = best;
    x[parameter] = value;
    ProfilePoint pt;
    pt.value = value;
    if (reoptimize && any_other && value != f.best_value) {
      const FitResult r = fit(objective, study, x, others, budget);
      pt.values = r.best;
      pt.chi2 = r.chi2;
    } else {
      const Evaluation e = objective.evaluate(x);
      pt.values = x;
      pt.chi2 = e.chi2;
    }
    pt.failed = pt.chi2 >= kFailedMisfit;
    pt.mu = residual_friction(study, parameter, f.peak_angle, value);
    f.profile.push_back(pt);
  }
  std::sort(f.profile.begin(), f.profile.end(), [](const auto& a, const auto& b) { return a.value < b.value; });
  f.profile.erase(std::unique(f.profile.begin(), f.profile.end(),
                              [](const auto& a, const auto& b) { return a.value == b.value; }),
                  f.profile.end());
  size_t at_min = 0;
  for (size_t k = 1; k < f.profile.size(); ++k)
    if (f.profile[k].chi2 < f.profile[at_min].chi2) at_min = k;
  for (ProfileRange* r : {&f.delta1, &f.delta4}) {
    *r = range_of(f.profile, at_min, f.profile[at_min].chi2, r == &f.delta1 ? 1.0 : 4.0);
    // mu falls as degradation (or roughness) rises: the low mu belongs to the high value.
    r->mu_low = residual_friction(study, parameter, f.peak_angle, r->high);
    r->mu_high = residual_friction(study, parameter, f.peak_angle, r->low);
  }
  return f;
}

}  // namespace ddafit::inverse
