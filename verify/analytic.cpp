#include "verify/analytic.hpp"

#include <algorithm>
#include <cmath>

namespace ddafit::verification {

double InclineAnalytic::acceleration(double d) const {
  const double deg = M_PI / 180.0;
  const double progress = critical_distance > 0 ? std::min(std::max(d, 0.0) / critical_distance, 1.0) : 1.0;
  const double phi = friction_angle - roughness_angle * progress;
  const double a = gravity * (std::sin(slope_angle * deg) - std::cos(slope_angle * deg) * std::tan(phi * deg));
  return std::max(a, 0.0);  // a block held by friction does not move uphill
}

void InclineAnalytic::solve(const std::vector<double>& times, std::vector<double>& distance,
                            std::vector<double>& speed) const {
  distance.assign(times.size(), 0.0);
  speed.assign(times.size(), 0.0);
  double t = 0.0, d = 0.0, v = 0.0;
  constexpr double h = 1e-5;
  for (size_t k = 0; k < times.size(); ++k) {
    while (t < times[k] - 1e-15) {
      const double step = std::min(h, times[k] - t);
      const double k1v = acceleration(d), k1d = v;
      const double k2v = acceleration(d + 0.5 * step * k1d), k2d = v + 0.5 * step * k1v;
      const double k3v = acceleration(d + 0.5 * step * k2d), k3d = v + 0.5 * step * k2v;
      const double k4v = acceleration(d + step * k3d), k4d = v + step * k3v;
      d += step / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
      v += step / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t += step;
    }
    distance[k] = d;
    speed[k] = v;
  }
}

double HousnerRocking::alpha() const { return std::atan(base / height); }

double HousnerRocking::frequency() const { return std::sqrt(3.0 * gravity / (2.0 * std::hypot(base, height))); }

double HousnerRocking::energy_kept() const { return std::pow(1.0 - 1.5 * std::pow(std::sin(alpha()), 2), 2); }

double HousnerRocking::energy(double theta) const { return std::cos(alpha() - theta) - std::cos(alpha()); }

double HousnerRocking::first_impact(double theta0) const {
  return std::acosh(alpha() / (alpha() - theta0)) / frequency();
}

double HousnerRocking::time_to_rest(double theta0) const {
  const double a = alpha();
  double t = first_impact(theta0), theta = theta0;
  for (int k = 0; k < 1000 && theta > 1e-7 * a; ++k) {
    theta = a - std::acos(std::cos(a) + energy_kept() * energy(theta));
    t += 2.0 * first_impact(theta);  // up to the peak and back down
  }
  return t;
}

RockingTrace rocking_trace(const std::vector<HistoryRow>& history) {
  RockingTrace out;
  double peak = 0.0;
  int sign = 0;
  for (size_t k = 0; k + 1 < history.size(); k += 2) {
    const Vec2 axis = history[k + 1].position - history[k].position;  // base to top
    const double tilt = std::atan2(axis.x(), axis.y());
    const int now = tilt > 0.0 ? 1 : -1;
    if (sign != 0 && now != sign) {
      if (out.first_impact < 0.0) out.first_impact = history[k].time;
      out.peaks.push_back(peak);
      peak = 0.0;
    }
    sign = now;
    peak = std::max(peak, std::abs(tilt));
  }
  return out;
}

}  // namespace ddafit::verification
