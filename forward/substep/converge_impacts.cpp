#include "forward/substep/converge_impacts.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "forward/contact/contact_law.hpp"
#include "forward/parallel.hpp"

namespace ddafit {
namespace {

// The largest rounds of the active set (points joining or leaving contact) per solve.
constexpr int kActiveSetRounds = 24;
// A share added to the Delassus matrix's diagonal: two points on one face and a block touching
// on several faces make the matrix singular, and the term picks the least-norm split. At 1e-6
// the floor's two points under a row took opposite impulses of 1e4 N s/m (a couple the
// rounding asked for) and the active set cycled; 1e-3 and 1e-2 soften the contacts enough
// to leave 15 % and 21 % rebounds (tests/test_impact_rebound.cpp); 1e-4 holds them.
constexpr double kRegularisation = 1e-4;
// Inside a group's solve a point joins the contacts once it closes faster than this share of
// the closing speed that starts a group: the group is solved to within it, not to the trigger's
// margin (at the margin itself a dropped block left a stack of ten sinking at 0.26 m/s).
constexpr double kSolveShare = 1e-2;
// A manifold next to a solved group joins it when the solve left it closing or pushing apart
// faster than this share of the trigger's speeds: a block the group pushed on at less than the
// trigger still has to be stopped by its neighbour (at the trigger itself a stack of ten took
// the impact in its top six blocks and the rest sank at 0.29 m/s).
constexpr double kGrowShare = 0.3;
// A solve may not leave the group more kinetic energy than the larger of its energy before the
// solve and before this substep's contact impulses, beyond this share (a frictionless
// inelastic solve never adds energy; the held friction and rounding may add a little, measured
// at up to 0.3 % on Vajont section I), plus half the group's mass times closing^2.
constexpr double kEnergyShare = 1e-2;
// After an impact, its group's blocks are held for ImpactConvergence::settle_substeps to this
// share of the trigger's speeds (0.3 |g| h closing at the default margins), and a group they
// start is grown at the same share: grown at the impact's margins, a settling group took in the
// middle of a stack of ten alone and left the blocks above it to the sweeps.
constexpr double kSettleShare = 0.03;
// A group solved and grown at the settling margins is left to the sweeps beyond this many
// points (an impact's group keeps ImpactConvergence::max_points): a stack of fifteen struck
// from above is 62 points (at 60 a 4 m block dropped on fifteen 4 x 1 m blocks at 0.4 m/s came
// back at 71 %). Measured with mark_struck on Vajont section VII degraded: 63 s of contact
// solve at 80 (54 s before mark_struck); at 100 one pair overlapped by 1.1 % of its block.
constexpr int kSettleMaxPoints = 80;
// A joint carries weight when its normal is within 45 deg of gravity (cos 45 deg).
constexpr double kWeightBearingCosine = 0.70710678118654752;

// A point's complementarity residual (Signorini: impulse >= its floor, residual >= 0, one of
// them at its bound): its normal velocity less the closing its gap allows within the substep
// (the speculative contact of solve_contacts.cpp).
// Of the blocks' velocities `v` (st.velocity unless given: mark_struck reads the free ones).
double residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h,
                const std::vector<Vec3>& v) {
  return normal_rate(m, p, v) + std::max(current_gap(m, p, st.step_moves), 0.0) / h;
}
double residual(const ContactManifold& m, const ContactPoint& p, const SweepState& st, double h) {
  return residual(m, p, st, h, st.velocity);
}

bool unresolved(const ContactManifold& m, const SweepState& st, double h, const ImpactConvergence& tolerance) {
  for (int q = 0; q < m.point_count; ++q) {
    const ContactPoint& p = m.points[q];
    const double r = residual(m, p, st, h);
    if (r < -tolerance.closing) return true;
    if (p.impulse.normal > -p.impulse.tension && r > tolerance.spent) return true;
  }
  return false;
}

// Adds manifold k's moving blocks and all their manifolds to the group's list.
void take_in(int k, const std::vector<ContactManifold>& manifolds, const BlockManifolds& of_block,
             const SweepState& st, std::vector<char>& involved, std::vector<char>& listed, std::vector<int>& list) {
  for (const int b : {manifolds[k].block_a, manifolds[k].block_b}) {
    if (involved[b] || !st.masses[b].moves) continue;
    involved[b] = 1;
    for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j)
      if (!listed[of_block.ids[j]]) listed[of_block.ids[j]] = 1, list.push_back(of_block.ids[j]);
  }
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

struct GroupPoint {
  int manifold, point;
};

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
        a(x, x) *= 1.0 + kRegularisation;
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

// The group's normal impulses solved together, the friction impulses held under their new
// Coulomb caps, then one sweep of the group so that friction settles with them (without it the
// walled row still threw the striker back at 18 %). Returns false, with nothing changed, when
// the answer would leave the group more kinetic energy than kEnergyShare allows.
bool solve_group(std::vector<ContactManifold>& manifolds, const std::vector<int>& list, const SweepSettings& relax,
                 const ImpactConvergence& settings, SweepState& st) {
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
    r0[i] = residual(m, p, st, h);
    lambda0[i] = p.impulse.normal;
    tangent0[i] = p.impulse.tangent;
    floor[i] = -p.impulse.tension;  // a bond holds tension down to its strength
  }
  Eigen::VectorXd d;
  solve_normal_impulses(delassus(manifolds, points, st), r0, lambda0, floor, kSolveShare * settings.closing, d);
  std::vector<Vec3> saved;
  for (const int b : blocks) saved.push_back(st.velocity[b]);
  const double before = std::max(kinetic_energy(blocks, st.velocity, st), kinetic_energy(blocks, st.free_velocity, st));
  double mass = 0.0;
  for (const int b : blocks) mass += 1.0 / st.masses[b].inverse_mass;
  for (int i = 0; i < n; ++i) {
    ContactManifold& m = manifolds[points[i].manifold];
    ContactPoint& p = m.points[points[i].point];
    const double normal = std::max(lambda0[i] + d[i], floor[i]);
    const double cap = coulomb_cap(m.friction, normal, p.impulse.cohesion);
    const double tangent = std::clamp(p.impulse.tangent, -cap, cap);
    apply_impulse(st.velocity[m.block_a], st.velocity[m.block_b], st.masses[m.block_a], st.masses[m.block_b], p,
                  (normal - p.impulse.normal) * m.normal + (tangent - p.impulse.tangent) * m.tangent);
    p.impulse.normal = normal;
    p.impulse.tangent = tangent;
  }
  char ignored = 0;
  for (const int k : list) solve_manifold(manifolds[k], ignored, relax, 1.0 / h, st);
  const double allowance = kEnergyShare * before + 0.5 * mass * settings.closing * settings.closing;
  if (kinetic_energy(blocks, st.velocity, st) <= before + allowance) return true;
  for (size_t x = 0; x < blocks.size(); ++x) st.velocity[blocks[x]] = saved[x];
  for (int i = 0; i < n; ++i) {
    ContactPoint& p = manifolds[points[i].manifold].points[points[i].point];
    p.impulse.normal = lambda0[i];
    p.impulse.tangent = tangent0[i];
  }
  return false;
}

int point_count(const std::vector<ContactManifold>& manifolds, const std::vector<int>& list) {
  int n = 0;
  for (const int k : list) n += manifolds[k].point_count;
  return n;
}

// One group: solved, then any manifold next to it that the solve left open (its block was
// driven by the group's) joins with its blocks and the group is solved again.
void converge_group(std::vector<ContactManifold>& manifolds, const BlockManifolds& of_block,
                    const SweepSettings& relax, const ImpactConvergence& settings, SweepState& st,
                    std::vector<char>& involved, std::vector<char>& listed, std::vector<int>& list,
                    ImpactCounts& counts) {
  const double h = relax.h;
  ImpactConvergence grow = settings;
  grow.closing *= kGrowShare;
  grow.spent *= kGrowShare;
  for (int round = 0; round < settings.max_rounds; ++round) {
    if (point_count(manifolds, list) > settings.max_points) {
      ++counts.too_large;
      return;
    }
    if (!solve_group(manifolds, list, relax, settings, st)) {
      ++counts.refused;
      return;
    }
    ++counts.solved;
    bool grew = false;
    const size_t listed_now = list.size();
    for (size_t i = 0; i < listed_now; ++i)
      for (const int b : {manifolds[list[i]].block_a, manifolds[list[i]].block_b}) {
        if (!st.masses[b].moves) continue;
        for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j) {
          const int other = of_block.ids[j];
          if (listed[other] || !unresolved(manifolds[other], st, h, grow)) continue;
          take_in(other, manifolds, of_block, st, involved, listed, list);
          grew = true;
        }
      }
    if (!grew) return;
  }
}

// Blocks struck through a weight-bearing joint settle (model revision 2026-11-28.7). A point
// whose blocks' free velocities (before any contact impulse this substep) were struck; when
// the two sweeps took the blow down a column they leave every joint closing under the margin,
// so no group starts, and the warm start of the next substeps (impulses that stopped the
// striker, re-applied to blocks at rest) throws the column up and the striker off: a 4 m block
// dropped at 0.5 m/s onto three 4 x 1 m blocks came back at 47 % of its speed (bound 24.6 %;
// tests/test_impact_rebound.cpp). Held to the settling margins for settle_substeps, the column
// is solved directly as it rebounds: 8.4 % (18.7 % worst over 384 slow drops onto stacks of
// 2-10 blocks, against 85 % before).
// A point is struck when the free velocities close it faster than the impact margin and close
// its gap within the substep (model revision 2026-11-28.8; .28.7 asked for the margin beyond
// the gap's allowance): a block arriving at a little over the margin was slowed to the 1 mm
// gap's allowance by the speculative contact in one substep and met the stack under the margin
// in the next, so it never marked (a 4 m block at 0.4 m/s onto six 1 m blocks came back at 39 %,
// bound 29.5 %; 16 of 576 slow drops onto stacks of 3-13 over their bound, none since).
// Only joints that carry weight (normal within 45 deg of gravity): a column's joints bear the
// weight above them and the impulses the warm start brings back; a row struck side-on bears
// none, and marking its joints too changed how a row of tall blocks rocked back onto its
// striker after an impact at 45 deg friction (6.4 % of 10 m/s against 1.2 %).
void mark_struck(const std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                 const ImpactConvergence& settings, SweepState& st) {
  if (settings.down.squaredNorm() == 0.0 || st.free_velocity.size() != st.velocity.size()) return;
  for (const ContactManifold& m : manifolds) {
    if (std::abs(m.normal.dot(settings.down)) < kWeightBearingCosine) continue;
    bool struck = false;
    for (int q = 0; q < m.point_count && !struck; ++q)
      struck = normal_rate(m, m.points[q], st.free_velocity) < -settings.closing &&
               residual(m, m.points[q], st, relax.h, st.free_velocity) < 0.0;
    if (!struck) continue;
    for (const int b : {m.block_a, m.block_b})
      if (st.masses[b].moves) st.settling_substeps[b] = std::max(st.settling_substeps[b], settings.settle_substeps);
  }
}

// A settling group solved at the tight margins holds the blocks of its weight-bearing joints
// settling for half of settle_substeps more (one step at the defaults; model revision
// 2026-11-28.8): a column still moving within itself when its two steps ran out was left to the
// sweeps and the warm start, and rose again (a 1 m block at 0.45 m/s onto twelve 0.25 m blocks
// at 35 deg: 44 % of its speed, bound 26.8 %, with the struck rule above alone). A column at
// rest needs no group, so the hold ends within a step of the column coming to rest.
void hold_settling(const std::vector<ContactManifold>& manifolds, const std::vector<int>& list,
                   const ImpactConvergence& settings, SweepState& st) {
  const int hold = settings.settle_substeps / 2;
  for (const int k : list) {
    const ContactManifold& m = manifolds[k];
    if (std::abs(m.normal.dot(settings.down)) < kWeightBearingCosine) continue;
    for (const int b : {m.block_a, m.block_b})
      if (st.masses[b].moves) st.settling_substeps[b] = std::max(st.settling_substeps[b], hold);
  }
}

int root_of(std::vector<int>& parent, int b) {
  while (parent[b] != b) b = parent[b] = parent[parent[b]];
  return b;
}

}  // namespace

ImpactCounts converge_impacts(std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                              const ImpactConvergence& settings, SweepState& st) {
  ImpactCounts counts;
  const long n = static_cast<long>(manifolds.size());
  std::vector<char> open(n, 0);
  const int blocks_n = static_cast<int>(st.velocity.size());
  if (static_cast<int>(st.settling_substeps.size()) != blocks_n) st.settling_substeps.assign(blocks_n, 0);
  ImpactConvergence tight = settings;
  tight.closing *= kSettleShare;
  tight.spent *= kSettleShare;
  tight.max_points = std::min(settings.max_points, kSettleMaxPoints);
  mark_struck(manifolds, relax, settings, st);
  const auto settling = [&](const ContactManifold& m) {
    return st.settling_substeps[m.block_a] > 0 || st.settling_substeps[m.block_b] > 0;
  };
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k)
    open[k] = unresolved(manifolds[k], st, relax.h, settings) ||
              (settling(manifolds[k]) && unresolved(manifolds[k], st, relax.h, tight));
  for (int& left : st.settling_substeps) left = std::max(left - 1, 0);
  if (std::find(open.begin(), open.end(), 1) == open.end()) return counts;
  // Impacts apart are solved apart. A group is an open manifold's moving blocks with all their
  // manifolds; two groups that share a manifold are one (solved one after the other, the second
  // would undo the first's answer at the manifold they share: a block dropped on a stack of ten
  // came back at 36 % of its speed).
  const BlockManifolds& of_block = block_manifolds(manifolds, st);
  const int blocks = static_cast<int>(st.velocity.size());
  std::vector<int> parent(blocks);
  for (int b = 0; b < blocks; ++b) parent[b] = b;
  const auto join = [&](int a, int b) {
    if (st.masses[a].moves && st.masses[b].moves) parent[root_of(parent, a)] = root_of(parent, b);
  };
  for (long k = 0; k < n; ++k) {
    if (!open[k]) continue;
    for (const int b : {manifolds[k].block_a, manifolds[k].block_b}) {
      if (!st.masses[b].moves) continue;
      for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j)
        join(manifolds[of_block.ids[j]].block_a, manifolds[of_block.ids[j]].block_b);
    }
  }
  std::vector<std::pair<int, int>> seeds;  // (group root, manifold)
  for (long k = 0; k < n; ++k) {
    if (!open[k]) continue;
    const ContactManifold& m = manifolds[k];
    seeds.push_back({root_of(parent, st.masses[m.block_a].moves ? m.block_a : m.block_b), static_cast<int>(k)});
  }
  std::stable_sort(seeds.begin(), seeds.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<char> involved(blocks, 0), listed(n, 0);
  for (size_t start = 0; start < seeds.size();) {
    size_t end = start;
    std::vector<int> list;
    for (; end < seeds.size() && seeds[end].first == seeds[start].first; ++end)
      take_in(seeds[end].second, manifolds, of_block, st, involved, listed, list);
    if (!list.empty()) {
      // A group seeded by a point beyond the impact margins is an impact: its blocks settle
      // for the next settle_substeps. A group seeded only by settling blocks is solved and
      // grown at the tight margins and holds its weight-bearing joints' blocks for half that
      // (hold_settling), not the whole settle_substeps. Judged when the group is
      // reached: an earlier group's growth may have taken in and solved a seed already.
      bool impact = false;
      for (size_t i = start; i < end; ++i) impact |= unresolved(manifolds[seeds[i].second], st, relax.h, settings);
      const long solved = counts.solved;
      converge_group(manifolds, of_block, relax, impact ? settings : tight, st, involved, listed, list, counts);
      if (!impact && counts.solved > solved) hold_settling(manifolds, list, settings, st);
      if (impact && counts.solved > solved)
        for (const int k : list)
          for (const int b : {manifolds[k].block_a, manifolds[k].block_b})
            if (st.masses[b].moves) st.settling_substeps[b] = settings.settle_substeps;
    }
    start = end;
  }
  return counts;
}

}  // namespace ddafit
