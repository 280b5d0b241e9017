// The global DDA system K D = F as 6x6 blocks (one per free block and per touching
// pair), and its sparse Cholesky solve with SuiteSparse CHOLMOD. CHOLMOD stays inside
// sparse_system.cpp (SparseSolver::Backend): nothing that includes this header compiles
// against SuiteSparse.
#pragma once

#include <cstdint>
#include <memory>
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

// What a solver has done so far: the cost drivers of docs/performance.md.
struct SolverCounters {
  long symbolic_analyses = 0;  // fill-reducing orderings (the contact graph changed)
  long factorizations = 0;     // numeric Cholesky factorisations
  long cg_solves = 0;          // solves finished by conjugate gradients on an older factor
  long cg_iterations = 0;      // all CG iterations, converged or not
};

// How SparseSolver reuses its work between solves.
struct SolverOptions {
  // Solve with conjugate gradients preconditioned by the last Cholesky factor, and
  // refactorise only when they would cost more than a factorisation. Between open-close
  // passes and between steps only a few contact springs change, which moves a few
  // eigenvalues of the preconditioned system away from 1, so a handful of iterations
  // gives the direct solution's accuracy (docs/performance.md).
  bool reuse_factorization = false;
  // Converged when |K x - F| <= tolerance |F|. Displacements are then exact to about
  // 1e-10 of a step's motion, far below the contact tolerance (1e-7 of it).
  double tolerance = 1e-10;
  // Never more iterations than this, whatever the measured costs say.
  int max_iterations = 60;
};

// Owns a CHOLMOD workspace and the last factor. The symbolic analysis (fill-reducing
// ordering and elimination tree) is kept while the block pattern does not change, so
// consecutive open-close iterations and steps with the same contacts only refactorise.
class SparseSolver {
 public:
  explicit SparseSolver(const SolverOptions& options = {});
  ~SparseSolver();
  SparseSolver(const SparseSolver&) = delete;
  SparseSolver& operator=(const SparseSolver&) = delete;

  // Solves K x = rhs. Returns false with a reason when K is not positive definite or
  // the result is not finite.
  bool solve(const BlockSparseMatrix& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
             std::string& reason);

  const SolverCounters& counters() const { return counters_; }

  // CHOLMOD's workspace, the last factor and its pattern, the CG timings; opaque outside
  // sparse_system.cpp.
  struct Backend;

 private:
  SolverOptions options_;
  SolverCounters counters_;
  std::unique_ptr<Backend> backend_;
};

}  // namespace ddafit
