#include "forward/earthquake/ground_motion.hpp"

#include <algorithm>

namespace ddafit {

GroundTrack::GroundTrack(const GroundMotion& motion) : time_(motion.time) {
  const size_t n = motion.time.size();
  acceleration_.resize(n);
  velocity_.assign(n, Vec2::Zero());
  displacement_.assign(n, Vec2::Zero());
  for (size_t i = 0; i < n; ++i) {
    acceleration_[i] = motion.scale * motion.acceleration[i];
    peak_ = std::max(peak_, acceleration_[i].norm());
  }
  // Exact integrals of the piecewise linear acceleration over each interval of length h:
  // v1 = v0 + h (a0 + a1) / 2,  u1 = u0 + h v0 + h^2 (2 a0 + a1) / 6.
  for (size_t i = 1; i < n; ++i) {
    const double h = time_[i] - time_[i - 1];
    const Vec2 &a0 = acceleration_[i - 1], &a1 = acceleration_[i];
    velocity_[i] = velocity_[i - 1] + 0.5 * h * (a0 + a1);
    displacement_[i] = displacement_[i - 1] + h * velocity_[i - 1] + h * h * (2.0 * a0 + a1) / 6.0;
  }
}

GroundState GroundTrack::at(double t) const {
  GroundState g;
  if (time_.empty() || t <= time_.front()) return g;  // at rest before the record starts
  if (t >= time_.back()) {
    // The record is over: no more acceleration; the ground keeps the velocity it ended with.
    g.velocity = velocity_.back();
    g.displacement = displacement_.back() + (t - time_.back()) * velocity_.back();
    return g;
  }
  const size_t i = static_cast<size_t>(std::upper_bound(time_.begin(), time_.end(), t) - time_.begin()) - 1;
  const double h = time_[i + 1] - time_[i], s = t - time_[i];
  const Vec2 &a0 = acceleration_[i], &a1 = acceleration_[i + 1];
  const Vec2 slope = (a1 - a0) / h;
  g.acceleration = a0 + s * slope;
  g.velocity = velocity_[i] + s * a0 + 0.5 * s * s * slope;
  g.displacement = displacement_[i] + s * velocity_[i] + 0.5 * s * s * a0 + s * s * s / 6.0 * slope;
  return g;
}

Vec2 GroundTrack::mean_acceleration(double t0, double t1) const {
  if (time_.empty() || !(t1 > t0)) return time_.empty() ? Vec2::Zero() : at(t0).acceleration;
  return (at(t1).velocity - at(t0).velocity) / (t1 - t0);
}

}  // namespace ddafit
