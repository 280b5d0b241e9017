// How the substep solver's sweeps walk the manifolds (docs/theory.md §13, "Threads and
// determinism"): colour by colour; each thread takes one contiguous share of a colour; and
// within its share a thread updates a few manifolds at once, their points in turn. The extra
// sweeps in list order walk it group by group (sweep_groups, list_groups.hpp).
//
// Why in batches: a manifold's passes are a chain of dependent updates (each impulse reads
// the block velocities the one before it wrote), so one manifold at a time leaves the core
// waiting on each link. The manifolds of one colour share no moving block, so the points of
// four of them can be updated in turn: four independent chains the core overlaps. Each
// manifold's own updates, and their order, are those of one manifold at a time, so the
// numbers are the same to the bit. On Vajont section VII degraded's first 10 s the two relax
// sweeps took a fifth less time in batches of four than one by one (eight: no better;
// docs/performance.md).
#pragma once

#include <omp.h>

#include <algorithm>
#include <vector>

#include "forward/contact/contact_types.hpp"
#include "forward/parallel.hpp"
#include "forward/substep/list_groups.hpp"
#include "forward/substep/prepare_contacts.hpp"

namespace ddafit {

// A colour this large is shared between the threads. Greedy colouring leaves a tail of
// small colours (a few hundred manifolds on Vajont section VII); at the general minimum of
// 512 the main thread swept them alone while the other waited.
inline constexpr long kColourParallelMinimum = 64;
// Manifolds updated in turn within a thread's share.
inline constexpr int kSweepBatch = 4;
// A manifold's passes stop when no impulse of a pass changed by more than this share of
// its largest normal impulse (control.contact_passes). 1e-2 since model revision
// 2026-11-27.2 (1e-3 before): the 96 slope landings of tests/test_landing.cpp land as
// well at either (3e-2 misses three), and Vajont section VII degraded's sweeps cost a
// quarter less (docs/performance.md).
inline constexpr double kManifoldPassTolerance = 1e-2;


// Calls batch(ids) with kSweepBatch manifold ids, or one(id) for a single one, for every
// manifold k of `colours` with take(k), colour by colour. Within a colour no two manifolds
// share a moving block, so neither the batches nor the thread count change the numbers;
// kSerialColour (manifolds that found no free colour) is swept one by one, in order.
// Each thread takes one contiguous share of a colour (the static schedule of 2026-11-29):
// manifolds are stored by piece pair, so a thread meets the same neighbourhood of the slide
// in every colour and every sweep, and the manifolds and velocities it writes stay in its
// own core's cache. In chunks of 32 handed out dynamically (before) they moved between the
// cores at every sweep, and two threads were no faster than one (docs/performance.md).
template <class Take, class Batch, class One>
void sweep_coloured(const std::vector<std::vector<int>>& colours, Take&& take, Batch&& batch, One&& one) {
  for (int c = 0; c < static_cast<int>(colours.size()); ++c) {
    const std::vector<int>& members = colours[c];
    const long n = static_cast<long>(members.size());
    if (c == kSerialColour) {
      for (long i = 0; i < n; ++i)
        if (take(members[i])) one(members[i]);
      continue;
    }
    const auto share = [&](long from, long to) {
      int ids[kSweepBatch];
      int count = 0;
      for (long i = from; i < to; ++i) {
        if (!take(members[i])) continue;
        ids[count++] = members[i];
        if (count == kSweepBatch) batch(static_cast<const int*>(ids)), count = 0;
      }
      for (int i = 0; i < count; ++i) one(ids[i]);
    };
    if (n < kColourParallelMinimum) {
      share(0, n);
      continue;
    }
#pragma omp parallel
    {
      const long t = omp_get_thread_num(), threads = omp_get_num_threads();
      const ThreadShare mine = thread_share(n, t, threads);
      share(mine.first, mine.last);
    }
  }
}

// What one point's update in a pass changed: the largest change of its impulses, and the
// size of its impulse that the change is judged against.
struct PassChange {
  double change = 0.0;
  double scale = 0.0;
};

// Passes over N manifolds at once, point q of each in turn (point(i, q) updates point q of
// manifold i), at most `passes`; a manifold stops once no change of a pass exceeds
// `tolerance` times the largest scale of that pass (control.contact_passes).
template <int N, class Point>
void converge_passes(ContactManifold* const* m, int passes, double tolerance, Point&& point) {
  bool open[N];
  for (int i = 0; i < N; ++i) open[i] = true;
  for (int pass = 0; pass < passes; ++pass) {
    int count[N];
    int most = 0;
    PassChange largest[N];
    for (int i = 0; i < N; ++i) {
      count[i] = open[i] ? m[i]->point_count : 0;
      most = std::max(most, count[i]);
    }
    if (most == 0) return;
    for (int q = 0; q < most; ++q)
      for (int i = 0; i < N; ++i) {
        if (q >= count[i]) continue;
        const PassChange r = point(i, q);
        largest[i].change = std::max(largest[i].change, r.change);
        largest[i].scale = std::max(largest[i].scale, r.scale);
      }
    for (int i = 0; i < N; ++i)
      if (open[i] && largest[i].change <= tolerance * largest[i].scale) open[i] = false;
  }
}

// Below this many manifold updates (the list's length times its sweeps) the groups run on the
// calling thread: the fork and barrier would cost more (parallel.hpp).
inline constexpr long kGroupParallelMinimum = 256;

// `sweeps` sweeps of each group, in list order: solve(k, flag) updates manifold k, `flag` a
// char of the calling thread's own for the caller's use. Each thread takes a contiguous run of
// groups, split by their manifolds' count (thread_share over ids).
template <class Solve>
void sweep_groups(const ListGroups& groups, int sweeps, Solve&& solve) {
  const int count = static_cast<int>(groups.first.size()) - 1;
  const auto run = [&](int from, int to) {
    char flag = 0;
    for (int g = from; g < to; ++g)
      for (int sweep = 0; sweep < sweeps; ++sweep)
        for (int i = groups.first[g]; i < groups.first[g + 1]; ++i) solve(groups.ids[i], flag);
  };
  const long n = static_cast<long>(groups.ids.size());
  if (count < 2 || n * sweeps < kGroupParallelMinimum) {
    run(0, count);
    return;
  }
#pragma omp parallel
  {
    const ThreadShare share = thread_share(n, omp_get_thread_num(), omp_get_num_threads());
    // The groups that start in this thread's share of the ids.
    int from = 0, to = 0;
    while (from < count && groups.first[from] < share.first) ++from;
    to = from;
    while (to < count && groups.first[to] < share.last) ++to;
    run(from, to);
  }
}

}  // namespace ddafit
