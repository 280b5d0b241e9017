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

}  // namespace ddafit::verification
