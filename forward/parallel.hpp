// When the substep solver's loops run on several threads.
#pragma once

namespace ddafit {

// Loops over fewer items than this run on one thread: the fork and barrier of a parallel
// loop (microseconds, and far worse when another process holds the other core) cost more
// than a few hundred blocks or contacts take to update. Several such loops run in every
// substep, thousands of times a second of simulation.
inline constexpr long kParallelMinimum = 512;

// Thread t's contiguous share [first, last) of n items split among `threads`: the same split
// for every loop over the same items, so the sweeps and the measurement of a step read the
// same neighbourhood of the slide on the same core.
struct ThreadShare {
  long first, last;
};
inline ThreadShare thread_share(long n, long t, long threads) { return {n * t / threads, n * (t + 1) / threads}; }

}  // namespace ddafit
