// The global DDA system K D = F as 6x6 blocks (one per free block and per touching
// pair), and its sparse Cholesky solve with SuiteSparse CHOLMOD.
#pragma once

#include <cholmod.h>

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "forward/kinematics.hpp"

namespace ddafit {

struct BlockSparseMatrix {
  int size = 0;                         // number of free blocks
  std::vector<Mat6> diagonal;           // K_aa
  std::vector<std::pair<int, int>> pairs;  // (a, b) with a < b, in order of first use
  std::vector<Mat6> off_diagonal;       // K_ab for each pair
  std::unordered_map<std::uint64_t, int> pair_index;

  void reset(int free_blocks);
  // K_ab += m (and K_ba += m^T implicitly). a == b adds to the diagonal.
  void add(int a, int b, const Mat6& m);
};

struct SolveStats {
  bool reused_analysis = false;
};

// Owns a CHOLMOD workspace and the last factor. The symbolic analysis (fill-reducing
// ordering and elimination tree) is kept while the block pattern does not change, so
// consecutive open-close iterations and steps with the same contacts only refactorise.
class SparseSolver {
 public:
  SparseSolver();
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  // Solves K x = rhs. Returns false with a reason when K is not positive definite or
  // the result is not finite.
  bool solve(const BlockSparseMatrix& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
             std::string& reason, SolveStats* stats = nullptr);

 private:
  cholmod_common common_;
  cholmod_factor* factor_ = nullptr;
  std::vector<int> pattern_columns_;
  std::vector<int> pattern_rows_;
};

}  // namespace ddafit
