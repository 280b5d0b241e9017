#include "forward/substep/solve_group_friction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "forward/contact/contact_law.hpp"

namespace ddafit {
namespace {

// Rounds of the stagger: each round solves with the caps mu N + c from the normal impulses of
// the round before. A heavy block landing on five light cubes (SubstepScenesHeavy): three
// rounds keep every cube within 7.5 mm.
constexpr int kCapRounds = 3;

// The contact problem with fixed caps is a strictly convex quadratic programme over a box:
//   minimise 1/2 d^T A d + w0^T d  over  lower <= y0 + d <= upper,
// A = J W J^T (the Delassus matrix of the normal and tangential rows, regularised), w0 the rows'
// velocities now. Its optimality conditions are the contact's: at a free impulse its velocity
// w = w0 + A d is zero (closing held, or sticking); at a normal impulse's floor w >= 0 (the point
// opens); at a friction cap w has the sign that opposes the impulse (the blocks slip against it).
// Solved by a primal active set that changes one bound at a time, which cannot cycle on a
// strictly convex programme (Nocedal & Wright, Numerical Optimization, §16.5): the pivoting on
// stick / slide / open states it replaces cycled on a heavy block landing on light cubes. A
// bound is released only when its velocity pulls off it by more than `tolerance`. Returns
// false when it has not settled within its iterations.
bool solve_box_programme(const Eigen::MatrixXd& A, const Eigen::VectorXd& w0, const Eigen::VectorXd& y0,
                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, double tolerance,
                         Eigen::VectorXd& d) {
  const int n = static_cast<int>(w0.size());
  std::vector<signed char> bound(n, 0);  // -1 at lower, +1 at upper, 0 free
  for (int i = 0; i < n; ++i) {
    const double y = std::clamp(y0[i] + d[i], lower[i], upper[i]);
    d[i] = y - y0[i];
    bound[i] = y <= lower[i] ? -1 : y >= upper[i] ? 1 : 0;
  }
  std::vector<int> free;
  for (int iteration = 0; iteration < 4 * n + 8; ++iteration) {
    const Eigen::VectorXd w = w0 + A * d;
    free.clear();
    for (int i = 0; i < n; ++i)
      if (bound[i] == 0) free.push_back(i);
    const int f = static_cast<int>(free.size());
    Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
    bool moves = false;
    if (f > 0) {
      Eigen::MatrixXd a(f, f);
      Eigen::VectorXd rhs(f);
      for (int x = 0; x < f; ++x) {
        rhs[x] = -w[free[x]];
        for (int y = 0; y < f; ++y) a(x, y) = A(free[x], free[y]);
      }
      // Free velocities within a thousandth of the tolerance: the free set is at its minimum.
      if (rhs.lpNorm<Eigen::Infinity>() > 1e-3 * tolerance) {
        const Eigen::VectorXd s = a.ldlt().solve(rhs);
        if (!s.allFinite()) return false;
        for (int x = 0; x < f; ++x) step[free[x]] = s[x];
        moves = true;
      }
    }
    if (moves) {  // as far along the step as the bounds allow; the first bound met joins
      double alpha = 1.0;
      int blocking = -1;
      for (const int i : free) {
        const double y = y0[i] + d[i];
        const double limit = step[i] < 0.0 ? lower[i] : upper[i];
        if (step[i] != 0.0 && std::isfinite(limit) && (y + step[i] - limit) * step[i] > 0.0) {
          const double t = std::max((limit - y) / step[i], 0.0);
          if (t < alpha) alpha = t, blocking = i;
        }
      }
      d += alpha * step;
      if (blocking >= 0) {
        bound[blocking] = step[blocking] < 0.0 ? -1 : 1;
        d[blocking] = (bound[blocking] < 0 ? lower[blocking] : upper[blocking]) - y0[blocking];
      }
      continue;
    }
    // At the minimum over the free set: release the bound whose velocity pulls off it most.
    int release = -1;
    double pull_most = tolerance;
    for (int i = 0; i < n; ++i) {
      const double pull = bound[i] < 0 ? -w[i] : bound[i] > 0 ? w[i] : 0.0;
      if (pull > pull_most) pull_most = pull, release = i;
    }
    if (release < 0) return true;
    bound[release] = 0;
  }
  return false;
}

}  // namespace

bool solve_friction_with_normals(const std::vector<ContactManifold>& manifolds, const std::vector<GroupPoint>& points,
                                 const std::vector<int>& blocks, const SweepState& st, const Eigen::VectorXd& r0,
                                 const Eigen::VectorXd& lambda0, const Eigen::VectorXd& tangent0,
                                 const Eigen::VectorXd& floor, double closing, const Eigen::VectorXd& dn0,
                                 Eigen::VectorXd& dn, Eigen::VectorXd& dt) {
  const int n = static_cast<int>(points.size());
  const int nb = static_cast<int>(blocks.size());
  std::vector<int> column(st.masses.size(), -1);
  for (int x = 0; x < nb; ++x) column[blocks[x]] = x;
  // Rows 2i (normal) and 2i + 1 (tangent) of the Jacobian over the group's moving blocks:
  // (dir, r x dir), negated on block a, so that a row times the velocities is the point's rate.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 3 * nb);
  Eigen::VectorXd inverse_mass(3 * nb), w0(2 * n), y0(2 * n), lower(2 * n), upper(2 * n), d(2 * n);
  for (int x = 0; x < nb; ++x) {
    const BlockMass& m = st.masses[blocks[x]];
    inverse_mass.segment<3>(3 * x) << m.inverse_mass, m.inverse_mass, m.inverse_inertia;
  }
  for (int i = 0; i < n; ++i) {
    const ContactManifold& m = manifolds[points[i].manifold];
    const ContactPoint& p = m.points[points[i].point];
    w0[2 * i] = r0[i];
    w0[2 * i + 1] = relative_rate(m.tangent, p, st.velocity[m.block_a], st.velocity[m.block_b]);
    y0[2 * i] = lambda0[i];
    y0[2 * i + 1] = tangent0[i];
    d[2 * i] = dn0[i];
    d[2 * i + 1] = 0.0;
    lower[2 * i] = floor[i];
    upper[2 * i] = std::numeric_limits<double>::infinity();
    for (int row = 0; row < 2; ++row) {
      const Vec2& dir = row == 0 ? m.normal : m.tangent;
      for (const auto& [block, r, sign] : {std::tuple{m.block_a, p.ra, -1.0}, std::tuple{m.block_b, p.rb, 1.0}}) {
        if (column[block] < 0) continue;
        const int x = 3 * column[block];
        J(2 * i + row, x) += sign * dir.x();
        J(2 * i + row, x + 1) += sign * dir.y();
        J(2 * i + row, x + 2) += sign * cross2(r, dir);
      }
    }
  }
  Eigen::MatrixXd A = J * inverse_mass.asDiagonal() * J.transpose();
  for (int i = 0; i < 2 * n; ++i) A(i, i) *= 1.0 + kDelassusRegularisation;
  for (int round = 0; round < kCapRounds; ++round) {
    for (int i = 0; i < n; ++i) {
      const ContactManifold& m = manifolds[points[i].manifold];
      const double cap = coulomb_cap(m.friction, y0[2 * i] + d[2 * i], m.points[points[i].point].impulse.cohesion);
      lower[2 * i + 1] = -cap;
      upper[2 * i + 1] = cap;
    }
    if (!solve_box_programme(A, w0, y0, lower, upper, closing, d)) return false;
  }
  dn = d(Eigen::seqN(0, n, 2));
  dt = d(Eigen::seqN(1, n, 2));
  return true;
}

}  // namespace ddafit
