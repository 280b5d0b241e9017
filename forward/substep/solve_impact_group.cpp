#include "forward/substep/solve_impact_group.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "forward/contact/contact_law.hpp"
#include "forward/substep/converge_heavy.hpp"
#include "forward/substep/solve_group_friction.hpp"

namespace ddafit {
namespace {

// The largest rounds of the active set (points joining or leaving contact) per solve.
constexpr int kActiveSetRounds = 24;
// Inside a group's solve a point joins the contacts once it closes faster than this share of
// the closing speed that starts a group: the group is solved to within it, not to the trigger's
// margin (at the margin itself a dropped block left a stack of ten sinking at 0.26 m/s).
constexpr double kSolveShare = 1e-2;
// A solve may not leave the group more kinetic energy than the larger of its energy before the
// solve and before this substep's contact impulses, beyond this share (a frictionless
// inelastic solve never adds energy; the held friction and rounding may add a little, measured
// at up to 0.3 % on Vajont section I), plus half the group's mass times closing^2.
constexpr double kEnergyShare = 1e-2;

// A group solves its friction with its normals (solve_group_friction.hpp) up to this many
// points (a dense programme over twice as many impulses). Its cost on Vajont section I degraded
// (substep, one thread): the whole wall 9.4 s without it, 9.3 s with it up to 64 points (the
// groups beside a heavy block there are mostly larger), 17.7 s at any size. A heavy block on
// five light cubes is 12-28 points.
constexpr int kFrictionMaxPoints = 64;

// Whether a manifold of the list joins two moving blocks one of which is at least `ratio`
// times the other's mass (never when ratio is 0).
bool has_heavy_pair(const std::vector<ContactManifold>& manifolds, const std::vector<int>& list, double ratio,
                    const SweepState& st) {
  if (ratio <= 0.0) return false;
  for (const int k : list) {
    const BlockMass& a = st.masses[manifolds[k].block_a];
    const BlockMass& b = st.masses[manifolds[k].block_b];
    if (a.moves && b.moves && (much_lighter(a, b, ratio) || much_lighter(b, a, ratio))) return true;
  }
  return false;
}

double kinetic_energy(const std::vector<int>& blocks, const std::vector<Vec3>& velocity, const SweepState& st) {
  double e = 0.0;
  for (const int b : blocks) {
    const BlockMass& m = st.masses[b];
    const Vec3& v = velocity[b];
    e += (v[0] * v[0] + v[1] * v[1]) / m.inverse_mass + (m.inverse_inertia > 0.0 ? v[2] * v[2] / m.inverse_inertia : 0.0);
  }
  return 0.5 * e;
}

// A point's row of the contact Jacobian on one block: (n, r x n), negated on block a, so that
// row . (v, w) summed over both blocks is the point's normal velocity (normal_rate).
struct JacobianRow {
  int block;
  Eigen::Vector3d row;
};

// The Delassus matrix A = J W J^T of the points (W the blocks' inverse masses and inertias):
// A d is the change of the points' normal velocities that normal impulses d make. Rows meet
// only on a shared moving block, so they are taken block by block (sorted by block): the
// cost is the sum of each block's rows squared, not (2n)^2. An entry gets at most two terms
// (its two points share at most both blocks), so the order of the sum does not change it.
Eigen::MatrixXd delassus(const std::vector<ContactManifold>& manifolds, const std::vector<GroupPoint>& points,
                         const SweepState& st) {
  const int n = static_cast<int>(points.size());
  std::vector<JacobianRow> rows;
  rows.reserve(2 * n);
  for (const GroupPoint& g : points) {
    const ContactManifold& m = manifolds[g.manifold];
    const ContactPoint& p = m.points[g.point];
    rows.push_back({m.block_a, -Eigen::Vector3d(m.normal.x(), m.normal.y(), cross2(p.ra, m.normal))});
    rows.push_back({m.block_b, Eigen::Vector3d(m.normal.x(), m.normal.y(), cross2(p.rb, m.normal))});
  }
  std::vector<int> order;
  order.reserve(2 * n);
  for (int i = 0; i < 2 * n; ++i)
    if (st.masses[rows[i].block].moves) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return rows[x].block != rows[y].block ? rows[x].block < rows[y].block : x < y;
  });
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (size_t first = 0; first < order.size();) {
    size_t last = first;
    while (last < order.size() && rows[order[last]].block == rows[order[first]].block) ++last;
    const BlockMass& mass = st.masses[rows[order[first]].block];
    for (size_t x = first; x < last; ++x) {
      const int i = order[x];
      const Eigen::Vector3d& r = rows[i].row;
      const Eigen::Vector3d w(mass.inverse_mass * r[0], mass.inverse_mass * r[1], mass.inverse_inertia * r[2]);
      for (size_t y = first; y < last; ++y) A(i / 2, order[y] / 2) += w.dot(rows[order[y]].row);
    }
    first = last;
  }
  return A;
}

// The linear complementarity problem of the points' normal impulses, by an active set: with
// impulses lambda0 and residuals r0 now, find changes d with lambda0 + d >= floor,
// r0 + A d >= 0 and one of them at its bound at every point. The points in contact solve
// A_SS d_S = -(r0_S + A_SN d_N) with the others at their floor; a point whose impulse would
// fall below its floor leaves, a point left closing faster than `closing` joins, until neither
// happens (the implicit solver's open-close iteration, on impulses), or for kActiveSetRounds
// rounds: the set can cycle between two answers, and the last one, held to the group's energy
// by solve_group, still stops a struck row (returning nothing then left rows at 33 %).
void solve_normal_impulses(const Eigen::MatrixXd& A, const Eigen::VectorXd& r0, const Eigen::VectorXd& lambda0,
                           const Eigen::VectorXd& floor, double closing, Eigen::VectorXd& d) {
  const int n = static_cast<int>(r0.size());
  std::vector<char> active(n);
  for (int i = 0; i < n; ++i) active[i] = lambda0[i] > floor[i] || r0[i] < -closing;
  d = Eigen::VectorXd::Zero(n);
  for (int round = 0; round < kActiveSetRounds; ++round) {
    std::vector<int> s;
    for (int i = 0; i < n; ++i) {
      if (active[i]) s.push_back(i);
      else d[i] = floor[i] - lambda0[i];
    }
    const int m = static_cast<int>(s.size());
    if (m > 0) {
      Eigen::VectorXd rhs(m);
      Eigen::MatrixXd a(m, m);
      for (int x = 0; x < m; ++x) {
        double known = r0[s[x]];
        for (int j = 0; j < n; ++j)
          if (!active[j]) known += A(s[x], j) * d[j];
        rhs[x] = -known;
        for (int y = 0; y < m; ++y) a(x, y) = A(s[x], s[y]);
        a(x, x) *= 1.0 + kDelassusRegularisation;
      }
      const Eigen::VectorXd ds = a.ldlt().solve(rhs);
      for (int x = 0; x < m; ++x) d[s[x]] = ds[x];
    }
    const Eigen::VectorXd r = r0 + A * d;
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      if (active[i] && lambda0[i] + d[i] < floor[i]) active[i] = 0, changed = true;
      else if (!active[i] && r[i] < -closing) active[i] = 1, changed = true;
    }
    if (!changed) return;
  }
}

}  // namespace

double impact_residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h,
                       const std::vector<Vec3>& v) {
  return normal_rate(m, p, v) + std::max(current_gap(m, p, st.step_moves), 0.0) / h;
}
double impact_residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h) {
  return impact_residual(m, p, st, h, st.velocity);
}

// The group's normal impulses solved together, the friction impulses held under their new
// Coulomb caps, then one sweep of the group so that friction settles with them (without it the
// walled row still threw the striker back at 18 %); or, in a group with a heavy block beside a
// light one, friction solved with the normals (solve_group_friction.hpp) and no sweep. Refused,
// with nothing changed, when the answer would leave the group more kinetic energy than
// kEnergyShare allows.
GroupSolve solve_impact_group(std::vector<ContactManifold>& manifolds, const std::vector<int>& list,
                              const SweepSettings& relax, double closing, double heavy_mass_ratio, SweepState& st) {
  const double h = relax.h;
  std::vector<GroupPoint> points;
  std::vector<int> blocks;
  for (const int k : list) {
    for (int q = 0; q < manifolds[k].point_count; ++q) points.push_back({k, q});
    for (const int b : {manifolds[k].block_a, manifolds[k].block_b})
      if (st.masses[b].moves) blocks.push_back(b);
  }
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  const int n = static_cast<int>(points.size());
  Eigen::VectorXd r0(n), lambda0(n), floor(n), tangent0(n);
  for (int i = 0; i < n; ++i) {
    const ContactManifold& m = manifolds[points[i].manifold];
    const ContactPoint& p = m.points[points[i].point];
    r0[i] = impact_residual(m, p, st, h);
    lambda0[i] = p.impulse.normal;
    tangent0[i] = p.impulse.tangent;
    floor[i] = -p.impulse.tension;  // a bond holds tension down to its strength
  }
  Eigen::VectorXd d;
  solve_normal_impulses(delassus(manifolds, points, st), r0, lambda0, floor, kSolveShare * closing, d);
  std::vector<Vec3> saved;
  for (const int b : blocks) saved.push_back(st.velocity[b]);
  const double before = std::max(kinetic_energy(blocks, st.velocity, st), kinetic_energy(blocks, st.free_velocity, st));
  double mass = 0.0;
  for (const int b : blocks) mass += 1.0 / st.masses[b].inverse_mass;
  Eigen::VectorXd dn, dt;
  const bool with_friction = n <= kFrictionMaxPoints && has_heavy_pair(manifolds, list, heavy_mass_ratio, st) &&
                             solve_friction_with_normals(manifolds, points, blocks, st, r0, lambda0, tangent0, floor,
                                                         kSolveShare * closing, d, dn, dt);
  for (int i = 0; i < n; ++i) {
    ContactManifold& m = manifolds[points[i].manifold];
    ContactPoint& p = m.points[points[i].point];
    const double normal = std::max(lambda0[i] + (with_friction ? dn[i] : d[i]), floor[i]);
    const double cap = coulomb_cap(m.friction, normal, p.impulse.cohesion);
    const double tangent = std::clamp(with_friction ? tangent0[i] + dt[i] : p.impulse.tangent, -cap, cap);
    apply_impulse(st.velocity[m.block_a], st.velocity[m.block_b], st.masses[m.block_a], st.masses[m.block_b], p,
                  (normal - p.impulse.normal) * m.normal + (tangent - p.impulse.tangent) * m.tangent);
    p.impulse.normal = normal;
    p.impulse.tangent = tangent;
  }
  // The sweep is skipped after a friction solve: it is Gauss-Seidel across the group's mass
  // ratio again, and un-solves what the programme solved. On ten 0.1 m cubes under a block 450
  // times as heavy (dropped 0.05 m, 20 deg, 10 ms x 3) it set the downslope end cube sliding
  // out from under the block at 0.25 m/s (7.3 mm against 5 mm; model revision 2026-12-05.5),
  // and Vajont section IV degraded overlapped by 1.34 % with it, 0.42 % without.
  char ignored = 0;
  if (!with_friction)
    for (const int k : list) solve_manifold(manifolds[k], ignored, relax, 1.0 / h, st);
  const double allowance = kEnergyShare * before + 0.5 * mass * closing * closing;
  if (kinetic_energy(blocks, st.velocity, st) <= before + allowance)
    return with_friction ? GroupSolve::NormalsAndFriction : GroupSolve::Normals;
  for (size_t x = 0; x < blocks.size(); ++x) st.velocity[blocks[x]] = saved[x];
  for (int i = 0; i < n; ++i) {
    ContactPoint& p = manifolds[points[i].manifold].points[points[i].point];
    p.impulse.normal = lambda0[i];
    p.impulse.tangent = tangent0[i];
  }
  return GroupSolve::Refused;
}

}  // namespace ddafit
