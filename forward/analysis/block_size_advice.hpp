// Block-size advice (`ddafit advise`): a ladder of block sizes, coarse to fine, each run as a
// small ensemble (forward/analysis/ensemble.hpp), and the coarsest size whose answer is
// within a tolerance of the next finer one's. The tolerance is never tighter than the runs'
// own spread: two means differ by noise alone up to about twice their combined standard
// deviation, so a pair is called converged when
//   |m_k - m_k+1| / |m_k+1| <= max(tolerance, 2 sqrt(s_k^2 + s_k+1^2) / |m_k+1|).
// When no pair converges the advice says plainly that the answer keeps moving with block
// size (the seed's finding: d_c scales with the block length, so a finer mesh is a different
// model, not only a more accurate one).
#pragma once

#include <string>
#include <vector>

#include "forward/analysis/ensemble.hpp"

namespace ddafit {

struct LadderRung {
  double block_size = 0.0;  // m
  int free_blocks = 0;
  Spread value;             // of the quantity over the rung's completed members
  int completed = 0;        // members that completed (0: the rung gives no answer)
  double wall_seconds = 0.0;
};

struct BlockSizeAdvice {
  std::vector<LadderRung> rungs;  // coarse to fine
  double tolerance = 0.05;
  std::vector<double> change;     // |m_k - m_k+1| / |m_k+1|, one per neighbouring pair
  std::vector<double> allowed;    // the tolerance the pair is held to (above)
  int recommended = -1;           // index into rungs; -1 when no pair converged
  std::string verdict;            // one sentence for the user
};

// Judges a ladder already run. Rungs without a completed member break the chain: a pair
// involving one never converges.
BlockSizeAdvice advise_block_size(std::vector<LadderRung> rungs, double tolerance);

}  // namespace ddafit
