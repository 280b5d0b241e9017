#include "forward/substep/integrate.hpp"
#include "forward/parallel.hpp"

#include <cmath>

#include "forward/common/displace_block.hpp"
#include "forward/water/hydrostatic.hpp"

namespace ddafit {

void water_accelerations(const BlockSystem& s, double gravity, double dt, SweepState& st) {
  if (!s.water.present()) {
    st.load_acceleration.clear();
    return;
  }
  st.load_acceleration.assign(s.blocks.size(), Vec3::Zero());
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    const BlockMass& m = st.masses[b];
    if (!m.moves) continue;
    const Vec6 load = water_load(s, static_cast<int>(b), gravity, 0.5 * dt * s.blocks[b].velocity.head<3>());
    st.load_acceleration[b] = Vec3(m.inverse_mass * load[0], m.inverse_mass * load[1], m.inverse_inertia * load[2]);
  }
}

void integrate_velocities(SweepState& st, const Vec2& gravity, double h, std::vector<Vec3>& start_velocity) {
  const long n = static_cast<long>(st.velocity.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    start_velocity[b] = st.velocity[b];
    if (!st.masses[b].moves) continue;
    st.velocity[b][0] += h * gravity.x();
    st.velocity[b][1] += h * gravity.y();
    if (!st.load_acceleration.empty()) st.velocity[b] += h * st.load_acceleration[b];
  }
}

void integrate_positions(SweepState& st, double h, const std::vector<Vec3>& start_velocity,
                         std::vector<Vec3>& moves, double smooth_acceleration) {
  const long n = static_cast<long>(st.velocity.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    const BlockMass& m = st.masses[b];
    if (!m.moves) continue;
    if (smooth_acceleration < 0.0) {
      moves[b] = 0.5 * h * (start_velocity[b] + st.velocity[b]);
    } else {
      Vec3 change = st.velocity[b] - start_velocity[b];
      double limit = h * smooth_acceleration;
      if (!st.load_acceleration.empty()) limit += 2.0 * h * st.load_acceleration[b].head<2>().norm();
      const double linear = change.head<2>().norm();
      if (linear > limit) change.head<2>() *= limit / linear;
      // The same bound on the turn, through the radius of gyration k = sqrt(I / m).
      const double k = m.inverse_inertia > 0.0 ? std::sqrt(m.inverse_mass / m.inverse_inertia) : 0.0;
      if (k > 0.0 && std::abs(change[2]) * k > limit) change[2] *= limit / (std::abs(change[2]) * k);
      moves[b] = h * st.velocity[b] - 0.5 * h * change;
    }
    st.step_moves[b] += moves[b];
  }
}

void add_push_out_moves(SweepState& st, double h, std::vector<Vec3>& moves) {
  const long n = static_cast<long>(st.velocity.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    if (!st.masses[b].moves) continue;
    const Vec3 push = h * st.push_velocity[b];
    moves[b] += push;
    st.step_moves[b] += push;
  }
}

void move_blocks(BlockSystem& s, const SweepState& st, bool measured) {
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    if (!st.masses[b].moves) continue;
    Vec6 d = Vec6::Zero();
    d.head<3>() = st.step_moves[b];
    displace_block(s, static_cast<int>(b), d, measured);
    s.blocks[b].velocity.head<3>() = st.velocity[b];
    s.blocks[b].velocity.tail<3>().setZero();
  }
}

}  // namespace ddafit
