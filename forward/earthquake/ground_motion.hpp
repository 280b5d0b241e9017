// The ground's motion during an earthquake and what the blocks feel of it.
//
// ddafit runs in the ground's frame. The fixed blocks stay where the scene puts them and every
// free block carries, besides its weight, the inertial load -m a_g(t) at its centroid (a_g =
// scale x the record). For a rigid ground this is the same problem as shaking the fixed blocks:
// the motion relative to the ground obeys the same equations, since the contacts see only
// relative motion. It was chosen over moving the fixed blocks because everything tied to the
// ground's geometry (the contact search's cached pairs, the water surface, the deposit's ground
// surface, the measure points' origins) stays fixed, and because what a Newmark analysis
// reports, the displacement relative to the ground, is then what the solvers integrate, with
// no difference of two large numbers. The absolute motion adds the ground's own (GroundTrack).
//
// The record is linear between samples and zero outside it: a record shorter than the run
// ends in stillness. The ground's velocity and displacement are its exact integrals from the
// record's start, so a step's velocity change from the shaking is exact whatever the step
// (mean_acceleration).
#pragma once

#include <vector>

#include "forward/scene.hpp"

namespace ddafit {

struct GroundState {
  Vec2 acceleration = Vec2::Zero();  // m/s^2
  Vec2 velocity = Vec2::Zero();      // m/s
  Vec2 displacement = Vec2::Zero();  // m
};

class GroundTrack {
 public:
  GroundTrack() = default;
  explicit GroundTrack(const GroundMotion& motion);

  bool present() const { return !time_.empty(); }

  // The ground at time t (run time; the record's times are run times).
  GroundState at(double t) const;

  // The mean acceleration over [t0, t1]: (v(t1) - v(t0)) / (t1 - t0).
  Vec2 mean_acceleration(double t0, double t1) const;

  // Largest |a_g| of the record, scaled.
  double peak_acceleration() const { return peak_; }

 private:
  std::vector<double> time_;
  std::vector<Vec2> acceleration_, velocity_, displacement_;  // scaled, at the samples
  double peak_ = 0.0;
};

}  // namespace ddafit
