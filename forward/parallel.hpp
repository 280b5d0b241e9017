// When the substep solver's loops run on several threads.
#pragma once

namespace ddafit {

// Loops over fewer items than this run on one thread: the fork and barrier of a parallel
// loop (microseconds, and far worse when another process holds the other core) cost more
// than a few hundred blocks or contacts take to update. Several such loops run in every
// substep, thousands of times a second of simulation.
inline constexpr long kParallelMinimum = 512;

}  // namespace ddafit
