// Shi's first-order block displacement field and the small dense types built on it.
#pragma once

#include <Eigen/Core>

#include "forward/scene.hpp"

namespace ddafit {

// Six unknowns of one block for one step: (u0, v0, r0, eps_x, eps_y, gamma_xy).
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat26 = Eigen::Matrix<double, 2, 6>;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// T(x, y) of Shi 1993 eq. 2.2: the displacement of material point p is T(p) * D for a
// block whose centroid is c.
inline Mat26 displacement_matrix(const Vec2& p, const Vec2& c) {
  const double X = p.x() - c.x();
  const double Y = p.y() - c.y();
  Mat26 t;
  t << 1.0, 0.0, -Y, X, 0.0, 0.5 * Y,
       0.0, 1.0, X, 0.0, Y, 0.5 * X;
  return t;
}

// T(p)^T * w without forming T: the generalised force of a point force w at p.
inline Vec6 displacement_matrix_transpose_times(const Vec2& p, const Vec2& c, const Vec2& w) {
  const double X = p.x() - c.x();
  const double Y = p.y() - c.y();
  Vec6 r;
  r << w.x(), w.y(), -Y * w.x() + X * w.y(), X * w.x(), Y * w.y(), 0.5 * (Y * w.x() + X * w.y());
  return r;
}

// Displacement of a material point over an accepted step with the rotation applied
// exactly (a rigid turn by r0 keeps lengths), the strain terms first order as in T.
// The first-order map would grow the block's area by (1 + r0^2) every step.
inline Vec2 exact_point_displacement(const Vec2& p, const Vec2& c, const Vec6& d) {
  const double X = p.x() - c.x();
  const double Y = p.y() - c.y();
  const double cr = std::cos(d[2]) - 1.0;
  const double sr = std::sin(d[2]);
  return Vec2(d[0] + cr * X - sr * Y + d[3] * X + 0.5 * d[5] * Y,
              d[1] + sr * X + cr * Y + d[4] * Y + 0.5 * d[5] * X);
}

// The rigid-body part of a block's motion, which both solvers' contact impulses act on.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Velocity of the material point at r (about the centroid) of a block moving with
// q = (vx, vy, w), the rigid-body part of its six rates; also its displacement for a
// small move q = (dx, dy, dtheta).
inline Vec2 velocity_at(const Vec3& q, const Vec2& r) { return Vec2(q[0] - q[2] * r.y(), q[1] + q[2] * r.x()); }

// 1 / (J W J^T) of a unit impulse along d at a point r_a, r_b from two blocks' centroids:
// 1 / (1/m_a + 1/m_b + (r_a x d)^2 / I_a + (r_b x d)^2 / I_b), from the inverse masses and
// moments of inertia (zero for a fixed block); 0 if both are fixed.
inline double rigid_effective_mass(double inverse_mass_a, double inverse_inertia_a, double inverse_mass_b,
                                   double inverse_inertia_b, const Vec2& ra, const Vec2& rb, const Vec2& d) {
  const double ca = cross2(ra, d), cb = cross2(rb, d);
  const double k = inverse_mass_a + inverse_mass_b + inverse_inertia_a * ca * ca + inverse_inertia_b * cb * cb;
  return k > 0.0 ? 1.0 / k : 0.0;
}

// Elastic matrix C relating (eps_x, eps_y, gamma_xy) to (sigma_x, sigma_y, tau_xy).
inline Mat3 elastic_matrix(double young_modulus, double poisson_ratio, bool plane_strain) {
  const double E = young_modulus, nu = poisson_ratio;
  Mat3 c = Mat3::Zero();
  if (plane_strain) {
    const double k = E / ((1.0 + nu) * (1.0 - 2.0 * nu));
    c << k * (1.0 - nu), k * nu, 0.0,
         k * nu, k * (1.0 - nu), 0.0,
         0.0, 0.0, k * (1.0 - 2.0 * nu) / 2.0;
  } else {
    const double k = E / (1.0 - nu * nu);
    c << k, k * nu, 0.0,
         k * nu, k, 0.0,
         0.0, 0.0, k * (1.0 - nu) / 2.0;
  }
  return c;
}

}  // namespace ddafit
