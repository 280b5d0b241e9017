#include "forward/substep/converge_impacts.hpp"

#include <algorithm>
#include <cmath>

#include "forward/parallel.hpp"
#include "forward/substep/solve_impact_group.hpp"

namespace ddafit {
namespace {

// A manifold next to a solved group joins it when the solve left it closing or pushing apart
// faster than this share of the trigger's speeds: a block the group pushed on at less than the
// trigger still has to be stopped by its neighbour (at the trigger itself a stack of ten took
// the impact in its top six blocks and the rest sank at 0.29 m/s).
constexpr double kGrowShare = 0.3;
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
// A too-large impact group is solved in pieces around the seeds that close faster than this
// many times the impact margin (converge_pieces). Vajont section VIII degraded to 21 s: a piece
// around every seed beyond the margin, 1,005,045 solves and 103 s of contact solve (44 s left to
// the sweeps); from 3 times the margin 94,893 solves, 48 s; from 6 times 29,704, 45 s. Worst
// overlap 0.42, 0.43 and 0.44 % (1.15 % left to the sweeps).
constexpr double kPieceShare = 3.0;
// A weight-bearing joint is struck when its blocks' free velocities close it faster than this
// share of the impact margin (mark_struck): 2 |g| h at the default margins, twice what gravity
// adds in a substep, so a joint that only carries weight is never struck. Over five sweeps of
// slow drops onto stacks (2,760 runs, 0.15-4 m/s, stacks of 2-15; tests/test_impact_rebound.cpp)
// the whole margin (.29.1) left 23 over their bound, 0.3 of it one (by 0.1 % of the speed), 0.2
// none.
constexpr double kStruckShare = 0.2;
// A settling group leaves out the joints that slip faster than this many times the impact margin
// (ImpactConvergence::slip; model revision 2026-12-04.2). Settling solves a struck column's
// joints directly so that the warm start does not throw it back up; a joint whose blocks slide
// past each other is no joint of a column at rest. Taken in, a heavy block sliding over light
// ones joined their group, and the direct solve, exact for rigid blocks, put the slider's load
// on the few blocks standing micrometres proud of the others; its friction there drove them
// and, through the row's joints, the blocks ahead. Sliders of 1 x 0.5 and 3 x 1.5 m arriving at
// 1-6 m/s on rows of 0.1 and 0.4 m cubes held at 60 deg (1 ms x 4): 18 of 72 drove the row
// (up to 19.6 m) or ran more than 1 % off seed Eq. 4; with the sliding joints left out, none
// (tests/test_free_row.cpp). At the impact margin itself a column of twenty struck at 5 m/s,
// whose joints slip while it stops, came back at 34 % of the speed (bound 7 %); at three times
// it, 5.5 % as before.
constexpr double kSlipShare = 3.0;
// A block already settling is struck again (settle_after_impact) when its group's solve raised
// a point's normal impulse beyond the warm start's by this many times the impact margin in its
// velocity. A heavy block dropped 0.2 m on five light cubes on a 10 deg floor (30 times a cube,
// 1 ms x 4) threw them 0.25 m without the rule and 7.5 mm with it; at 3 times the margin blocks
// dropped at 2-10 m/s onto a column of thirty came back at up to 24.6 % of their speed (13.9 %
// without the rule, 12.7 % at 10 times); marking every impact group's blocks struck put a slow drop onto
// fifteen 0.25 m blocks at 33.8 % (bound 30 %; tests/test_impact_rebound.cpp).
constexpr double kStruckAgainShare = 10.0;
// A joint carries weight when its normal is within 45 deg of gravity (cos 45 deg).
constexpr double kWeightBearingCosine = 0.70710678118654752;

// Whether m's blocks slide past each other faster than `speed` at one of its points. An impact's
// group takes every joint (infinite `speed`): no point is read.
bool slipping(const ContactManifold& m, const SweepState& st, double speed) {
  if (std::isinf(speed)) return false;
  for (int q = 0; q < m.point_count; ++q)
    if (std::abs(relative_rate(m.tangent, m.points[q], st.velocity[m.block_a], st.velocity[m.block_b])) > speed)
      return true;
  return false;
}

bool unresolved(const ContactManifold& m, const SweepState& st, double h, const ImpactConvergence& tolerance) {
  for (int q = 0; q < m.point_count; ++q) {
    const ContactPoint& p = m.points[q];
    const double r = impact_residual(m, p, st, h);
    if (r < -tolerance.closing) return true;
    if (p.impulse.normal > -p.impulse.tension && r > tolerance.spent) return true;
  }
  return false;
}

// Adds manifold k's moving blocks and all their manifolds but those slipping faster than `slip`
// (ImpactConvergence::slip) to the group's list.
void take_in(int k, const std::vector<ContactManifold>& manifolds, const BlockManifolds& of_block,
             const SweepState& st, double slip, std::vector<char>& involved, std::vector<char>& listed,
             std::vector<int>& list) {
  for (const int b : {manifolds[k].block_a, manifolds[k].block_b}) {
    if (involved[b] || !st.masses[b].moves) continue;
    involved[b] = 1;
    for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j) {
      const int other = of_block.ids[j];
      if (!listed[other] && !slipping(manifolds[other], st, slip)) listed[other] = 1, list.push_back(other);
    }
  }
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
    const GroupSolve solve = solve_impact_group(manifolds, list, relax, settings.closing, settings.heavy_mass_ratio, st);
    if (solve == GroupSolve::Refused) {
      ++counts.refused;
      return;
    }
    ++counts.solved;
    if (solve == GroupSolve::NormalsAndFriction) ++counts.with_friction;
    bool grew = false;
    const size_t listed_now = list.size();
    for (size_t i = 0; i < listed_now; ++i)
      for (const int b : {manifolds[list[i]].block_a, manifolds[list[i]].block_b}) {
        if (!st.masses[b].moves) continue;
        for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j) {
          const int other = of_block.ids[j];
          if (listed[other] || slipping(manifolds[other], st, settings.slip) ||
              !unresolved(manifolds[other], st, h, grow))
            continue;
          take_in(other, manifolds, of_block, st, settings.slip, involved, listed, list);
          grew = true;
        }
      }
    if (!grew) return;
  }
}

// Blocks struck through a weight-bearing joint settle (model revision 2026-11-28.7). When the
// two sweeps take a blow down a column they leave every joint closing under the impact margin,
// so no group starts, and the warm start of the next substeps (impulses that stopped the
// striker, re-applied to blocks at rest) throws the column up and the striker off: a 4 m block
// dropped at 0.5 m/s onto three 4 x 1 m blocks came back at 47 % of its speed (bound 24.6 %;
// tests/test_impact_rebound.cpp). So a point that the blocks' free velocities (before any
// contact impulse this substep) close faster than kStruckShare of the impact margin, and
// close beyond its gap within the substep, marks both blocks settling for settle_substeps, and
// the column is solved directly as it rebounds. History of the rule, all on slow drops onto
// stacks: .28.7 asked for the whole margin beyond the gap's allowance (18.7 % worst over 384
// drops, 85 % before); a block arriving at a little over the margin was slowed to its 1 mm
// gap's allowance in one substep and met the stack under the margin in the next, never marked
// (a 4 m block at 0.4 m/s onto six 1 m blocks: 39 %, bound 29.5 %), hence the gap's test since
// .28.8; and a column's top blocks that hopped and landed again under the margin rocked the
// column up again (a 1 m block at 0.45 m/s onto twelve 0.25 m blocks: 44 %, bound 26.8 %; drops
// at 0.15-0.25 m/s: up to 95 %), hence kStruckShare since .29.2.
// Only joints that carry weight (normal within 45 deg of gravity): a column's joints bear the
// weight above them and the impulses the warm start brings back; a row struck side-on bears
// none, and marking its joints too changed how a row of tall blocks rocked back onto its
// striker after an impact at 45 deg friction (6.4 % of 10 m/s against 1.2 %).
void mark_struck(const std::vector<ContactManifold>& manifolds, const SweepSettings& relax,
                 const ImpactConvergence& settings, SweepState& st) {
  if (settings.down.squaredNorm() == 0.0 || st.free_velocity.size() != st.velocity.size()) return;
  // The test in parallel, the marks after it in order (a largest value, so the same either way).
  const long n = static_cast<long>(manifolds.size());
  std::vector<char> struck(n, 0);
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    const ContactManifold& m = manifolds[k];
    if (std::abs(m.normal.dot(settings.down)) < kWeightBearingCosine) continue;
    for (int q = 0; q < m.point_count && !struck[k]; ++q)
      struck[k] = normal_rate(m, m.points[q], st.free_velocity) < -kStruckShare * settings.closing &&
                  impact_residual(m, m.points[q], st, relax.h, st.free_velocity) < 0.0;
  }
  for (long k = 0; k < n; ++k) {
    if (!struck[k]) continue;
    for (const int b : {manifolds[k].block_a, manifolds[k].block_b})
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

// Whether the group's solve gave block b, at one of m's points, a blow: a normal impulse beyond
// the one its warm start carried in that changes b's velocity by more than kStruckAgainShare
// times the impact margin (Delta v = Delta P_n / m_b).
bool struck_again(const ContactManifold& m, int b, const SweepState& st, const ImpactConvergence& settings) {
  for (int q = 0; q < m.point_count; ++q) {
    const ImpulseState& i = m.points[q].impulse;
    if ((i.normal - std::max(i.carried, 0.0)) * st.masses[b].inverse_mass > kStruckAgainShare * settings.closing)
      return true;
  }
  return false;
}

// The blocks of a group solved for an impact settle for the next settle_substeps; those not
// settling already are struck now, and the next warm start hands on only the impulses their
// points carried into the impact (solve_contacts.hpp, warm_start). A block already settling is
// struck again when the group dealt it a blow of its own (struck_again; model revision
// 2026-12-05.3): a heavy block landing on a row of light cubes was set settling by the landing's
// first group and stopped by the next (-1.20 to -0.05 m/s), and the warm start after that,
// not capped, handed on the whole stopping impulse and threw it off at +1.73 m/s.
void settle_after_impact(const std::vector<ContactManifold>& manifolds, const std::vector<int>& list,
                         const ImpactConvergence& settings, SweepState& st) {
  if (st.struck_now.size() != st.velocity.size()) st.struck_now.assign(st.velocity.size(), 0);
  for (const int k : list)
    for (const int b : {manifolds[k].block_a, manifolds[k].block_b}) {
      if (!st.masses[b].moves) continue;
      if (st.settling_substeps[b] == 0 || struck_again(manifolds[k], b, st, settings)) st.struck_now[b] = 1;
      st.settling_substeps[b] = settings.settle_substeps;
    }
}

// A group too large to solve whole (an impact spread through a sliding mass: thousands of
// manifolds) is solved piece by piece around its impacts, deepest first: each seed closing faster
// than kPieceShare times the impact margin, with all the manifolds of its blocks, grown as any
// group is up to max_points, the rest of the mass held at the answer it has (a block Gauss-Seidel
// over the group's pieces). Left whole to the sweeps, a 1.7 m sliver crushed between two blocks of
// a group of about 7,000 manifolds closed at 3 m/s for 0.08 s and overlapped its neighbour by
// 1.15 % (Vajont section VIII degraded, revision 2026-11-28.8). Groups of settling blocks only
// stay with the sweeps: they close under the impact margin. `involved` and `listed` come in
// clear and are left clear.
void converge_pieces(std::vector<ContactManifold>& manifolds, const BlockManifolds& of_block,
                     const SweepSettings& relax, const ImpactConvergence& settings, SweepState& st,
                     const std::vector<int>& seeds, std::vector<char>& involved, std::vector<char>& listed,
                     ImpactCounts& counts) {
  const double h = relax.h;
  std::vector<std::pair<double, int>> deepest;  // (worst residual, manifold)
  for (const int k : seeds) {
    double worst = 0.0;
    for (int q = 0; q < manifolds[k].point_count; ++q)
      worst = std::min(worst, impact_residual(manifolds[k], manifolds[k].points[q], st, h));
    if (worst < -kPieceShare * settings.closing) deepest.push_back({worst, k});
  }
  std::stable_sort(deepest.begin(), deepest.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<int> list;
  for (const auto& [worst, k] : deepest) {
    if (!unresolved(manifolds[k], st, h, settings)) continue;  // an earlier piece took it
    list.clear();
    take_in(k, manifolds, of_block, st, settings.slip, involved, listed, list);
    if (point_count(manifolds, list) > settings.max_points) {  // its blocks alone are too many
      for (const int j : list) listed[j] = 0;
      list.assign(1, k);
      listed[k] = 1;
    }
    ImpactCounts piece;
    converge_group(manifolds, of_block, relax, settings, st, involved, listed, list, piece);
    counts.pieces += piece.solved;
    counts.refused += piece.refused;
    counts.with_friction += piece.with_friction;
    if (piece.solved > 0) settle_after_impact(manifolds, list, settings, st);
    for (const int j : list) {
      listed[j] = 0;
      involved[manifolds[j].block_a] = involved[manifolds[j].block_b] = 0;
    }
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
  tight.slip = kSlipShare * settings.closing;
  mark_struck(manifolds, relax, settings, st);
  const auto settling = [&](const ContactManifold& m) {
    return st.settling_substeps[m.block_a] > 0 || st.settling_substeps[m.block_b] > 0;
  };
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k)
    open[k] = unresolved(manifolds[k], st, relax.h, settings) ||
              (settling(manifolds[k]) && !slipping(manifolds[k], st, tight.slip) &&
               unresolved(manifolds[k], st, relax.h, tight));
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
  // Each block's manifolds are joined once, however many open manifolds it has: joining a
  // pair already together changes no root, so the groups and their roots are as before.
  const std::vector<std::array<int, 2>>& pairs = pair_blocks(manifolds, st);
  std::vector<char> joined(blocks, 0);
  for (long k = 0; k < n; ++k) {
    if (!open[k]) continue;
    for (const int b : pairs[k]) {
      if (!st.masses[b].moves || joined[b]) continue;
      joined[b] = 1;
      for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j)
        join(pairs[of_block.ids[j]][0], pairs[of_block.ids[j]][1]);
    }
  }
  std::vector<std::pair<int, int>> seeds;  // (group root, manifold)
  for (long k = 0; k < n; ++k) {
    if (!open[k]) continue;
    const ContactManifold& m = manifolds[k];
    seeds.push_back({root_of(parent, st.masses[m.block_a].moves ? m.block_a : m.block_b), static_cast<int>(k)});
  }
  std::stable_sort(seeds.begin(), seeds.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<char> involved(blocks, 0), listed(n, 0), piece_involved(blocks, 0), piece_listed(n, 0);
  for (size_t start = 0; start < seeds.size();) {
    size_t end = start;
    while (end < seeds.size() && seeds[end].first == seeds[start].first) ++end;
    // A group seeded by a point beyond the impact margins is an impact: its blocks settle for
    // the next settle_substeps. A group seeded only by settling blocks is solved and grown at
    // the tight margins, without its slipping joints, and holds its weight-bearing joints'
    // blocks for half that (hold_settling), not the whole settle_substeps. Judged when the
    // group is reached: an earlier group's growth may have taken in and solved a seed already.
    bool impact = false;
    for (size_t i = start; i < end; ++i) impact |= unresolved(manifolds[seeds[i].second], st, relax.h, settings);
    const ImpactConvergence& margins = impact ? settings : tight;
    std::vector<int> list;
    for (size_t i = start; i < end; ++i)
      take_in(seeds[i].second, manifolds, of_block, st, margins.slip, involved, listed, list);
    if (!list.empty()) {
      if (impact && point_count(manifolds, list) > margins.max_points) {
        ++counts.too_large;
        std::vector<int> group_seeds;
        for (size_t i = start; i < end; ++i) group_seeds.push_back(seeds[i].second);
        converge_pieces(manifolds, of_block, relax, settings, st, group_seeds, piece_involved, piece_listed, counts);
        start = end;
        continue;
      }
      const long solved = counts.solved;
      converge_group(manifolds, of_block, relax, margins, st, involved, listed, list, counts);
      if (!impact && counts.solved > solved) hold_settling(manifolds, list, settings, st);
      if (impact && counts.solved > solved) settle_after_impact(manifolds, list, settings, st);
    }
    start = end;
  }
  return counts;
}

}  // namespace ddafit
