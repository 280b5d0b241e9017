// The change between two assemblies of the DDA system, K_now - K_then, as a few rank-one
// terms, so that a Cholesky factor of K_then can be updated to one of K_now instead of
// refactorised (factor_update.cpp). Between two open-close passes of a step the blocks'
// terms and the contact geometry are the same; only the points that changed state differ: a
// point that closes adds its normal spring p g g^T (g = d(d_n)/dD over the two blocks'
// unknowns, point_springs.hpp), one that locks adds its shear spring, one that opens or starts
// sliding takes them away (docs/theory.md, "Open-close passes as factor updates").
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "forward/kinematics.hpp"

namespace ddafit {

// A contact spring's share of K: stiffness x g g^T, with g = (a on free block i's unknowns,
// b on free block j's; a side is -1 for a fixed block). Its key names the point and the spring
// (normal or shear) within the step's contact list; springs are recorded in increasing key.
struct SpringTerm {
  std::uint64_t key = 0;
  int i = -1, j = -1;
  double stiffness = 0.0;
  Vec6 a = Vec6::Zero(), b = Vec6::Zero();
  bool operator==(const SpringTerm&) const = default;
};

// One rank-one term v v^T: v's nonzeros (rows of the global system, 6 x free block + unknown).
struct RankOneTerm {
  std::vector<int> rows;
  std::vector<double> values;
};

struct LowRankChange {
  bool representable = false;          // false: refactorise
  std::vector<RankOneTerm> updates;    // K_now - K_then = sum updates v v^T - sum downdates v v^T
  std::vector<RankOneTerm> downdates;
  int rank() const { return static_cast<int>(updates.size() + downdates.size()); }
};

// What an assembly of K is made of, as far as its changes go: its size (free blocks), the
// pairs of free blocks it couples (its pattern), the blocks' own terms (inertia, elasticity)
// and the contact springs, each as added (sparse_system.hpp, BlockSparseMatrix).
struct AssembledTerms {
  int size = 0;
  std::vector<std::pair<int, int>> pairs;
  std::vector<Mat6> block_terms;
  std::vector<SpringTerm> springs;
};

// K_now - K_then from the two assemblies' spring lists: a spring in `now` only is an update,
// one in `then` only a downdate, one that differs (a stiffer penalty) both. Not representable
// when the two have different sizes or block pairs (the contact graph changed) or the change
// has more than `max_rank` terms, or the blocks' own terms differ (another step: a new step
// length, blocks that turned). factor_update.cpp checks each solution against K_now itself.
LowRankChange low_rank_change(const AssembledTerms& then, const AssembledTerms& now, int max_rank);

}  // namespace ddafit
