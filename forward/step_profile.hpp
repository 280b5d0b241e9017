// Wall time spent in each stage of the time step (Box2D's b2Profile is the model).
#pragma once

#include <chrono>

namespace ddafit {

struct StepProfile {
  double settle = 0.0;          // pre-loading the contacts touching at t = 0, s
  double find_contacts = 0.0;   // broad and narrow phase, s
  double assemble = 0.0;        // block and contact terms, s
  double solve = 0.0;           // CHOLMOD analysis, factorisation and solve, s
  double check_contacts = 0.0;  // open-close classification, s
  double update = 0.0;          // moving blocks, velocities, stresses, slips, s
  double total = 0.0;           // whole run, s
};

// Adds the elapsed time of its scope to one field of a profile.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& sink) : sink_(sink), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    sink_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double& sink_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace ddafit
