#include "forward/substep/solve_contacts.hpp"
#include "forward/parallel.hpp"
#include "forward/substep/coloured_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "forward/contact/contact_law.hpp"
#include "forward/contact/slip_history.hpp"
#include "forward/substep/prepare_contacts.hpp"

namespace ddafit {
ContactSoftness make_softness(double hertz, double zeta, double h) {
  if (hertz <= 0.0) return {0.0, 1.0};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  return {omega / a1, a2 / (1.0 + a2)};
}

namespace {

// No tension past a bond's cut-off (prepare_contacts set it for this substep) is handed on
// (model revision 2026-12-06.16). The quiet start holds bonded joints glued
// (prepare_contacts.cpp), so the clock may start with a joint loaded past it:
//   - the joint as a whole (its points' net pull against the sum of their cut-offs): the weight
//     overloads it, and it tears and hands on no tension. Handed on at the cut-off, the stale
//     tension of the joints that tore threw the top block of eight 4 m blocks bonded at half
//     their weight up, and the energy audit stopped the run in its second step (kinetic energy
//     726 J/m against 604 J/m of gravity's work; tests/test_bonds.cpp);
//   - one point only (the uphill corner of a bonded column's base, which the glued quiet start
//     loads past it while the rest of the joint presses): that point carries its cut-off and
//     the rest of the base the rest. Torn, the columns of tests/test_cohesive_slope.cpp bonded
//     at 1.5 times their holding strength unzipped and toppled.
// A point without a bond never carries tension, so a scene without bonds is unchanged.
void cap_carried_tension(ContactManifold& m) {
  bool past = false;
  double net = 0.0, capacity = 0.0;
  for (int q = 0; q < m.point_count; ++q) {
    const ImpulseState& i = m.points[q].impulse;
    past |= i.normal < -i.tension;
    net += i.normal;
    capacity += i.tension;
  }
  if (!past) return;
  const bool torn = -net > capacity;
  for (int q = 0; q < m.point_count; ++q) {
    ImpulseState& i = m.points[q].impulse;
    if (torn && i.normal < 0.0) i.normal = 0.0;
    else if (i.normal < -i.tension) i.normal = -i.tension;
  }
}

// Warm start at one point (warm_start below).
inline void warm_point(const ContactManifold& m, ContactPoint& p, bool struck, Vec3& va, Vec3& vb, const BlockMass& ma,
                       const BlockMass& mb) {
  ImpulseState& i = p.impulse;
  if (struck && i.normal > std::max(i.carried, 0.0)) {  // the blow's share is not handed on
    const double resting = std::max(i.carried, 0.0);
    i.tangent *= resting / i.normal;
    i.normal = resting;
  }
  i.carried = i.normal;
  apply_impulse(va, vb, ma, mb, p, i.normal * m.normal + i.tangent * m.tangent);
}

template <int N>
void warm_batch(std::vector<ContactManifold>& manifolds, const int* ids, bool any_struck, SweepState& st) {
  ContactManifold* m[N];
  bool struck[N];
  int most = 0;
  for (int i = 0; i < N; ++i) {
    m[i] = &manifolds[ids[i]];
    struck[i] = any_struck && (st.struck_now[m[i]->block_a] || st.struck_now[m[i]->block_b]);
    most = std::max(most, m[i]->point_count);
    if (st.bonds) cap_carried_tension(*m[i]);
  }
  for (int q = 0; q < most; ++q)
    for (int i = 0; i < N; ++i)
      if (q < m[i]->point_count)
        warm_point(*m[i], m[i]->points[q], struck[i], st.velocity[m[i]->block_a], st.velocity[m[i]->block_b],
                   st.masses[m[i]->block_a], st.masses[m[i]->block_b]);
}

constexpr auto kEvery = [](int) { return true; };

}  // namespace

void warm_start(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                SweepState& st) {
  const bool any_struck = std::find(st.struck_now.begin(), st.struck_now.end(), 1) != st.struck_now.end();
  sweep_coloured(
      colours, kEvery, [&](const int* ids) { warm_batch<kSweepBatch>(manifolds, ids, any_struck, st); },
      [&](int k) { warm_batch<1>(manifolds, &k, any_struck, st); });
  if (any_struck) std::fill(st.struck_now.begin(), st.struck_now.end(), 0);
}

namespace {

// One point of a pass: the normal impulse with the push-out (or none in the relax sweep),
// then friction under the Mohr-Coulomb cap. Returns the larger change of its two impulses,
// judged against its normal impulse.
inline PassChange point_pass(const ContactManifold& m, ContactPoint& p, char& deep, const SweepSettings& settings,
                             double inv_h, const SweepState& st, Vec3& va, Vec3& vb, const BlockMass& ma,
                             const BlockMass& mb) {
  // Normal: the gap now, from the step's start and the blocks' moves since.
  const double gap = current_gap(m, p, st.step_moves);
  // The push-out of an overlap follows the soft spring (bias rate and mass scale), but
  // the impulse is not relaxed towards zero as Box2D's soft contact does: that leak
  // makes the overlap that holds a load F equal F / (m w^2), and with m the effective
  // mass of a small block under a 200 m thick mass it sank a 3 m triangle 0.9 m into
  // the bedrock (Vajont section VII stopped at 5.6-23 s; without it the run finishes).
  double bias = 0.0, mass_scale = 1.0;
  if (gap > 0.0) {
    bias = gap * inv_h;  // speculative: may close the gap within the substep, not more
  } else if (settings.use_bias) {
    bias = std::max(settings.softness.bias_rate * std::min(0.0, gap + settings.linear_slop),
                    -settings.max_pushout_speed);
    mass_scale = settings.softness.mass_scale;
  }
  if (!settings.use_bias && gap < -m.deep_overlap) deep = 1;
  const double vn = relative_rate(m.normal, p, va, vb);
  const double change = -p.impulse.normal_mass * mass_scale * (vn + bias);
  // Contact law: compression only, unless a bond holds tension (tension cut-off).
  const double total = std::max(p.impulse.normal + change, -p.impulse.tension);
  const double normal_change = total - p.impulse.normal;
  apply_impulse(va, vb, ma, mb, p, normal_change * m.normal);
  p.impulse.normal = total;

  // Friction: the Mohr-Coulomb cap, mu N (seed Eq. 2-3 for mu) plus cohesion while bonded.
  const double cap = coulomb_cap(m.friction, p.impulse.normal, p.impulse.cohesion);
  const double vt = relative_rate(m.tangent, p, va, vb);
  const double tangent = std::clamp(p.impulse.tangent - p.impulse.tangent_mass * vt, -cap, cap);
  apply_impulse(va, vb, ma, mb, p, (tangent - p.impulse.tangent) * m.tangent);
  const PassChange result{std::max(std::abs(normal_change), std::abs(tangent - p.impulse.tangent)), std::abs(total)};
  p.impulse.tangent = tangent;
  return result;
}

// N manifolds of one colour (or one manifold) solved at once (coloured_sweep.hpp).
// The friction impulse at a point below a block's centre turns the block, which moves the
// normal velocity at both points; one pass leaves that coupling unconverged where an
// impact's friction should nearly stop the slip (a landing near the friction angle). Local
// passes are Gauss-Seidel on each manifold alone: the fixed point is the sweep's own,
// reached in fewer sweeps.
template <int N>
void solve_batch(ContactManifold* const* m, char* const* deep, const SweepSettings& settings, double inv_h,
                 SweepState& st) {
  // The blocks' velocities are held in locals through the passes and stored once: no two
  // manifolds of a batch share a moving block, and a fixed block's velocity never changes.
  Vec3 va[N], vb[N];
  BlockMass ma[N], mb[N];
  for (int i = 0; i < N; ++i) {
    va[i] = st.velocity[m[i]->block_a], vb[i] = st.velocity[m[i]->block_b];
    ma[i] = st.masses[m[i]->block_a], mb[i] = st.masses[m[i]->block_b];
  }
  converge_passes<N>(m, settings.manifold_passes, kManifoldPassTolerance, [&](int i, int q) {
    return point_pass(*m[i], m[i]->points[q], *deep[i], settings, inv_h, st, va[i], vb[i], ma[i], mb[i]);
  });
  for (int i = 0; i < N; ++i) {
    if (ma[i].moves) st.velocity[m[i]->block_a] = va[i];
    if (mb[i].moves) st.velocity[m[i]->block_b] = vb[i];
  }
}

}  // namespace

// One manifold of a sweep: passes over its points until they agree.
void solve_manifold(ContactManifold& m, char& deep, const SweepSettings& settings, double inv_h, SweepState& st) {
  ContactManifold* const one[1] = {&m};
  char* const flag[1] = {&deep};
  solve_batch<1>(one, flag, settings, inv_h, st);
}

std::vector<int> deep_neighbourhood(const std::vector<ContactManifold>& manifolds, SweepState& st,
                                    std::vector<char>& involved) {
  involved.assign(st.velocity.size(), 0);
  const std::vector<std::array<int, 2>>& pairs = pair_blocks(manifolds, st);
  bool any = false;
  for (int k = 0; k < static_cast<int>(st.deep.size()); ++k)
    if (st.deep[k]) involved[pairs[k][0]] = involved[pairs[k][1]] = 1, any = true;
  if (!any) return {};
  return manifolds_of_blocks(pairs, involved, st.masses);
}

std::vector<int> manifolds_of_blocks(const std::vector<std::array<int, 2>>& pairs, const std::vector<char>& marked,
                                     const std::vector<BlockMass>& masses) {
  std::vector<int> list;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const auto [a, b] = pairs[k];
    if ((marked[a] && masses[a].moves) || (marked[b] && masses[b].moves)) list.push_back(k);
  }
  return list;
}

BlockManifolds::BlockManifolds(const std::vector<ContactManifold>& manifolds, size_t blocks) : first(blocks + 1, 0) {
  for (const ContactManifold& m : manifolds) ++first[m.block_a + 1], ++first[m.block_b + 1];
  for (size_t b = 0; b < blocks; ++b) first[b + 1] += first[b];
  ids.resize(first[blocks]);
  std::vector<int> next(first.begin(), first.end() - 1);
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k)
    ids[next[manifolds[k].block_a]++] = k, ids[next[manifolds[k].block_b]++] = k;
}

const std::vector<std::array<int, 2>>& pair_blocks(const std::vector<ContactManifold>& manifolds, SweepState& st) {
  if (st.pair_blocks.size() != manifolds.size()) {
    st.pair_blocks.resize(manifolds.size());
    for (size_t k = 0; k < manifolds.size(); ++k) st.pair_blocks[k] = {manifolds[k].block_a, manifolds[k].block_b};
  }
  return st.pair_blocks;
}

const BlockManifolds& block_manifolds(const std::vector<ContactManifold>& manifolds, SweepState& st) {
  if (!st.of_block) st.of_block.emplace(manifolds, st.velocity.size());
  return *st.of_block;
}

void solve_contacts(std::vector<ContactManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                    const SweepSettings& settings, SweepState& st) {
  const double inv_h = 1.0 / settings.h;
  const auto batch = [&](const int* ids) {
    ContactManifold* m[kSweepBatch];
    char* deep[kSweepBatch];
    for (int i = 0; i < kSweepBatch; ++i) m[i] = &manifolds[ids[i]], deep[i] = &st.deep[ids[i]];
    solve_batch<kSweepBatch>(m, deep, settings, inv_h, st);
  };
  sweep_coloured(colours, kEvery, batch, [&](int k) { solve_manifold(manifolds[k], st.deep[k], settings, inv_h, st); });
}

namespace {

// A point of m whose gap after a move of h at its present closing speed would pass deep_overlap.
bool closing_deep(const ContactManifold& m, double h, const SweepState& st) {
  for (int q = 0; q < m.point_count; ++q) {
    const ContactPoint& p = m.points[q];
    const double vn = normal_rate(m, p, st.velocity);
    if (current_gap(m, p, st.step_moves) + h * std::min(vn, 0.0) < -m.deep_overlap) return true;
  }
  return false;
}

// Far blocks: moving blocks outside `involved` that a listed manifold touches. A far block
// that one of its unlisted manifolds would now carry deep joins the neighbourhood with all
// its manifolds. Returns whether any joined.
// Whether a far block's manifold closes deep does not change while blocks join (no sweep runs
// in between), so it is read first for every manifold of every far block, in parallel
// (`closing`, per manifold: 1 closes deep, 0 not, -1 not read); the joining, in list order,
// then only looks it up.
bool bring_in_driven(const std::vector<ContactManifold>& manifolds, const BlockManifolds& of_block, double h,
                     const SweepState& st, std::vector<char>& involved, std::vector<char>& listed,
                     std::vector<int>& list, std::vector<signed char>& closing) {
  const size_t n = list.size();
  std::vector<int> far;  // the far blocks' unlisted manifolds, each once
  for (size_t i = 0; i < n; ++i) {
    const ContactManifold& m = manifolds[list[i]];
    for (const int b : {m.block_a, m.block_b}) {
      if (involved[b] || !st.masses[b].moves) continue;
      for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j) {
        const int k = of_block.ids[j];
        if (!listed[k] && closing[k] < 0) closing[k] = 0, far.push_back(k);
      }
    }
  }
  const long count = static_cast<long>(far.size());
#pragma omp parallel for schedule(static) if (count >= kParallelMinimum)
  for (long i = 0; i < count; ++i) closing[far[i]] = closing_deep(manifolds[far[i]], h, st) ? 1 : 0;
  bool grew = false;
  for (size_t i = 0; i < n; ++i) {
    const ContactManifold& m = manifolds[list[i]];
    for (const int b : {m.block_a, m.block_b}) {
      if (involved[b] || !st.masses[b].moves) continue;
      bool driven = false;
      for (int j = of_block.first[b]; j < of_block.first[b + 1] && !driven; ++j)
        driven = !listed[of_block.ids[j]] && closing[of_block.ids[j]] > 0;
      if (!driven) continue;
      involved[b] = 1, grew = true;
      for (int j = of_block.first[b]; j < of_block.first[b + 1]; ++j)
        if (!listed[of_block.ids[j]]) listed[of_block.ids[j]] = 1, list.push_back(of_block.ids[j]);
    }
  }
  for (const int k : far) closing[k] = -1;
  return grew;
}

// converge_deep's rounds of bringing in driven far blocks, at most.
constexpr int kDrivenRounds = 4;

}  // namespace

void flag_closing_deep(const std::vector<ContactManifold>& manifolds, double h, SweepState& st) {
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k)
    if (!st.deep[k] && closing_deep(manifolds[k], h, st)) st.deep[k] = 1;
}

void converge_deep(std::vector<ContactManifold>& manifolds, const SweepSettings& relax, int iterations,
                   SweepState& st, double closing_h) {
  std::vector<char> involved;
  std::vector<int> list = deep_neighbourhood(manifolds, st, involved);
  if (list.empty()) return;
  const double inv_h = 1.0 / relax.h;
  ListGroups groups;
  const auto sweeps = [&] {
    group_by_blocks(list, pair_blocks(manifolds, st), st.masses, groups);
    sweep_groups(groups, iterations,
                 [&](int k, char& ignored) { solve_manifold(manifolds[k], ignored, relax, inv_h, st); });
  };
  sweeps();
  if (closing_h <= 0.0) return;
  const BlockManifolds& of_block = block_manifolds(manifolds, st);
  std::vector<char> listed(manifolds.size(), 0);
  for (const int k : list) listed[k] = 1;
  std::vector<signed char> closing(manifolds.size(), -1);
  for (int round = 0; round < kDrivenRounds; ++round) {
    if (!bring_in_driven(manifolds, of_block, closing_h, st, involved, listed, list, closing)) break;
    sweeps();
  }
}

void advance_slip(const BlockSystem& s, const std::vector<Vec3>& moves, double h, double tolerance,
                  ContactSet& contacts) {
  std::vector<ContactManifold>& manifolds = contacts.manifolds;
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    ContactManifold& m = manifolds[k];
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      p.impulse.step_normal += p.impulse.normal;
      p.impulse.step_tangent += p.impulse.tangent;
      if (p.bonded) {
        // The bond (contact_law.hpp, wear_bond): lost once the point has slid or opened at
        // its strength by more than the slop.
        const bool sliding =
            std::abs(p.impulse.tangent) >= 0.999 * coulomb_cap(m.friction, p.impulse.normal, p.impulse.cohesion);
        const bool torn = p.impulse.normal <= -0.999 * p.impulse.tension;
        wear_bond(p, sliding ? relative_rate(m.tangent, p, moves[m.block_a], moves[m.block_b]) : 0.0,
                  torn ? normal_rate(m, p, moves) : 0.0, tolerance);
        if (!p.bonded) p.impulse.cohesion = p.impulse.tension = 0.0;
      }
      if (!p.bonded && p.impulse.normal <= 0.0) {
        // Open: no slip, no load.
        p.slip = 0.0;
        p.normal_load = 0.0;
        continue;
      }
      p.slip = std::abs(relative_rate(m.tangent, p, moves[m.block_a], moves[m.block_b]));
      p.normal_load = h > 0.0 ? std::max(p.impulse.normal, 0.0) / h : 0.0;
    }
  }
  advance_histories(s, contacts, h);
}

}  // namespace ddafit
