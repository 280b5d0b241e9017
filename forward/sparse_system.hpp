// The global DDA system K D = F as 6x6 blocks (one per free block and per touching
// pair), and its sparse Cholesky solve with SuiteSparse CHOLMOD. CHOLMOD stays inside
// sparse_system.cpp and factor_update.cpp (sparse_backend.hpp, SparseBackend): nothing that
// includes this header compiles against SuiteSparse.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "forward/kinematics.hpp"
#include "forward/low_rank_change.hpp"

namespace ddafit {

struct SparseBackend;  // CHOLMOD's side of SparseSolver (sparse_backend.hpp)

struct BlockSparseMatrix {
  int size = 0;                         // number of free blocks
  std::vector<Mat6> diagonal;           // K_aa
  std::vector<std::pair<int, int>> pairs;  // (a, b) with a < b, in order of first use
  std::vector<Mat6> off_diagonal;       // K_ab for each pair
  std::unordered_map<std::uint64_t, int> pair_index;
  // The blocks' own terms (inertia, elasticity) and the contact springs included above, as
  // they were added: within a step only the springs change from one open-close pass to the next
  // (low_rank_change.hpp); from step to step the blocks' terms change with the step and their shapes.
  std::vector<Mat6> block_terms;
  std::vector<SpringTerm> springs;

  void reset(int free_blocks);
  // K_ab += m (and K_ba += m^T implicitly). a == b adds to the diagonal.
  void add(int a, int b, const Mat6& m);
  // The index of pair (a, b), a != b, in `pairs`, added with a zero block if new; then
  // add_to_pair(index, a < b, m) is add(a, b, m) without looking the pair up again.
  int pair(int a, int b);
  void add_to_pair(int index, bool a_first, const Mat6& m) {
    if (a_first)
      off_diagonal[index] += m;
    else
      off_diagonal[index] += m.transpose();
  }
};

// What a solver has done so far: the cost drivers of docs/performance.md.
struct SolverCounters {
  long symbolic_analyses = 0;  // fill-reducing orderings (the contact graph changed)
  long factorizations = 0;     // numeric Cholesky factorisations
  long cg_solves = 0;          // solves finished by conjugate gradients on an older factor
  long cg_iterations = 0;      // all CG iterations, converged or not
  long factor_updates = 0;     // passes solved on the last factor updated by a few rank-one terms
  long update_rank = 0;        // rank-one terms applied in those updates
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
  // Update the last factor by the rank-one terms of the change in K (low_rank_change.hpp)
  // instead of refactorising, when the change is a few contact springs: between open-close
  // passes only the points that changed state differ. The solution is checked against K
  // (update_tolerance, below) and the pass refactorised otherwise.
  bool update_factorization = true;
  // A solution on an updated factor must leave |K x - F| <= update_tolerance |F| (after at most
  // one step of refinement). Direct and updated solves leave 1e-14 to 1e-13 on the brick walls;
  // 1e-10 let a collision's momentum drift by 3e-9 over its run.
  double update_tolerance = 1e-12;
  // Refactorise instead when the update's estimated cost is more than this share of a
  // factorisation's (factor_update.cpp, note_ordering).
  // 0.1: the factorisation works in dense BLAS-3 kernels, the update column by column, at
  // about a tenth of the rate per entry (shares 0.02 / 0.05 / 0.1 / 0.2 on the brick walls of
  // docs/performance.md: 0.1 fastest on both).
  double update_cost_share = 0.1;
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

 private:
  SolverOptions options_;
  SolverCounters counters_;
  std::unique_ptr<SparseBackend> backend_;
};

}  // namespace ddafit
