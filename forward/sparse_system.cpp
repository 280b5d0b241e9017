#include "forward/sparse_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include <omp.h>

#include "forward/sparse_backend.hpp"

namespace ddafit {
namespace {

// Debian's CHOLMOD 5.12 opens an OpenMP team of 4 threads (CHOLMOD_OMP_NUM_THREADS, fixed
// when it was built) for loops inside every supernode, whatever --threads says. On a DDA system
// (6x6 blocks, supernodes of a few dozen columns) each team wakes and parks its threads for
// microseconds of work: the 411-block brick wall made 471,000 futex calls in 30 steps, and its
// factorisations took twice as long as on one thread (bench/peer, docs/performance.md). With
// max-active-levels at 0 every region CHOLMOD opens runs on the calling thread alone; the
// whole solve (factorisation, factor update, copies, triangular solves) runs in this scope.
// (libgomp still signals from inside cholmod_super_numeric: 265,000 futex wakes on that wall's
// 150 steps, without waiters.) The setting is restored when the last solve in progress ends
// (a study may run several forward models on threads of its own, and the setting is the
// process's), so the substep solver's own loops are untouched.
class CholmodOnOneThread {
 public:
  CholmodOnOneThread() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (in_progress_++ == 0) {
      saved_levels_ = omp_get_max_active_levels();
      omp_set_max_active_levels(0);
    }
  }
  ~CholmodOnOneThread() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (--in_progress_ == 0) omp_set_max_active_levels(saved_levels_);
  }
  CholmodOnOneThread(const CholmodOnOneThread&) = delete;
  CholmodOnOneThread& operator=(const CholmodOnOneThread&) = delete;

 private:
  static inline std::mutex mutex_;
  static inline int in_progress_ = 0;
  static inline int saved_levels_ = 1;
};

// Copies k's terms into `terms`, reusing its storage.
void remember_terms(const BlockSparseMatrix& k, AssembledTerms& terms) {
  terms.size = k.size;
  terms.pairs = k.pairs;
  terms.block_terms = k.block_terms;
  terms.springs = k.springs;
}

bool refactorize(SparseBackend& be, SolverCounters& counters, cholmod_sparse* a, int n, std::string& reason);
bool preconditioned_cg(SparseBackend& be, const SolverOptions& options, cholmod_sparse* a,
                       const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations);

}  // namespace

void BlockSparseMatrix::reset(int free_blocks) {
  size = free_blocks;
  diagonal.assign(free_blocks, Mat6::Zero());
  pairs.clear();
  off_diagonal.clear();
  pair_index.clear();
  block_terms.clear();
  springs.clear();
}

int BlockSparseMatrix::pair(int a, int b) {
  const int lo = std::min(a, b), hi = std::max(a, b);
  const std::uint64_t key = (static_cast<std::uint64_t>(lo) << 32) | static_cast<std::uint32_t>(hi);
  auto [it, inserted] = pair_index.emplace(key, static_cast<int>(pairs.size()));
  if (inserted) {
    pairs.emplace_back(lo, hi);
    off_diagonal.push_back(Mat6::Zero());
  }
  return it->second;
}

void BlockSparseMatrix::add(int a, int b, const Mat6& m) {
  if (a == b) {
    diagonal[a] += m;
    return;
  }
  const bool swap = a > b;
  const int lo = swap ? b : a, hi = swap ? a : b;
  const std::uint64_t key = (static_cast<std::uint64_t>(lo) << 32) | static_cast<std::uint32_t>(hi);
  auto [it, inserted] = pair_index.emplace(key, static_cast<int>(pairs.size()));
  if (inserted) {
    pairs.emplace_back(lo, hi);
    off_diagonal.push_back(Mat6::Zero());
  }
  if (swap)
    off_diagonal[it->second] += m.transpose();
  else
    off_diagonal[it->second] += m;
}

SparseSolver::SparseSolver(const SolverOptions& options) : options_(options), backend_(std::make_unique<SparseBackend>()) {
  cholmod_start(&backend_->common);
  backend_->common.print = 0;
  backend_->common.error_handler = nullptr;
  // Supernodes twice as relaxed as CHOLMOD's defaults (nrelax 4/16/48 columns, zrelax
  // 0.8/0.1/0.05): a DDA matrix is made of 6x6 blocks, and its default supernodes are small
  // (182 on the 411-block wall, 2460 columns). Fewer, larger ones cost a few more zeros but
  // fewer dense kernel calls: 1.2 s less of 6.5 s on that wall (docs/performance.md).
  for (int i = 0; i < 3; ++i) {
    backend_->common.nrelax[i] *= 2;
    backend_->common.zrelax[i] *= 2.0;
  }
}

SparseSolver::~SparseSolver() {
  if (backend_->factor) cholmod_free_factor(&backend_->factor, &backend_->common);
  if (backend_->updated) cholmod_free_factor(&backend_->updated, &backend_->common);
  if (backend_->matrix) cholmod_free_sparse(&backend_->matrix, &backend_->common);
  cholmod_finish(&backend_->common);
}

bool SparseSolver::solve(const BlockSparseMatrix& k, const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                         std::string& reason) {
  SparseBackend& be = *backend_;
  const CholmodOnOneThread one_thread;
  const int nb = k.size;
  const int n = 6 * nb;
  if (n == 0) {
    x.resize(0);
    return true;
  }
  // Upper triangle in compressed columns: block column b holds the pairs (a, b), a < b,
  // in increasing a, then the upper part of K_bb.
  std::vector<int> order(k.pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int p, int q) {
    return k.pairs[p].second != k.pairs[q].second ? k.pairs[p].second < k.pairs[q].second
                                                  : k.pairs[p].first < k.pairs[q].first;
  });
  std::vector<int> column_start(nb + 1, 0);
  for (const auto& pr : k.pairs) ++column_start[pr.second + 1];
  for (int b = 0; b < nb; ++b) column_start[b + 1] += column_start[b];

  const size_t nnz = 36 * k.pairs.size() + 21 * static_cast<size_t>(nb);
  if (be.matrix && (static_cast<int>(be.matrix->nrow) != n || be.matrix->nzmax < nnz))
    cholmod_free_sparse(&be.matrix, &be.common);
  if (!be.matrix) be.matrix = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &be.common);
  cholmod_sparse* a = be.matrix;
  auto* ap = static_cast<int*>(a->p);
  auto* ai = static_cast<int*>(a->i);
  auto* ax = static_cast<double*>(a->x);
  int pos = 0;
  for (int b = 0; b < nb; ++b) {
    for (int c = 0; c < 6; ++c) {
      ap[6 * b + c] = pos;
      for (int q = column_start[b]; q < column_start[b + 1]; ++q) {
        const int p = order[q];
        const int row_block = k.pairs[p].first;
        for (int r = 0; r < 6; ++r) {
          ai[pos] = 6 * row_block + r;
          ax[pos++] = k.off_diagonal[p](r, c);
        }
      }
      for (int r = 0; r <= c; ++r) {
        ai[pos] = 6 * b + r;
        ax[pos++] = k.diagonal[b](r, c);
      }
    }
  }
  ap[n] = pos;

  const bool warm = options_.reuse_factorization && be.factor != nullptr && static_cast<int>(be.factor->n) == n &&
                    be.last_solution.size() == n;
  if (warm) {
    x = be.last_solution;
    int iterations = 0;
    const bool converged = preconditioned_cg(be, options_, a, rhs, x, iterations);
    counters_.cg_iterations += iterations;
    if (converged && x.allFinite()) {
      ++counters_.cg_solves;
      be.last_solution = x;
      return true;
    }
  }
  if (options_.update_factorization && be.factored_valid && be.factor != nullptr &&
      static_cast<int>(be.factor->n) == n) {
    remember_terms(k, be.current);
    const int rank = solve_updated(be, be.current, a, rhs, x, options_.update_cost_share, options_.update_tolerance);
    if (rank >= 0) {
      ++counters_.factor_updates;
      counters_.update_rank += rank;
      be.last_solution = x;
      return true;
    }
  }
  be.factored_valid = false;
  const bool ok = refactorize(be, counters_, a, n, reason);
  if (!ok) return false;
  if (options_.update_factorization) {
    remember_terms(k, be.factored);
    be.factored_valid = true;
  }
  if (!solve_with(be.factor, be.common, rhs, x)) {
    reason = "CHOLMOD solve failed (status " + std::to_string(be.common.status) + ")";
    return false;
  }
  if (!x.allFinite()) {
    reason = "the solution has non-finite values (ill-conditioned system: penalty too stiff?)";
    return false;
  }
  be.last_solution = x;
  return true;
}

namespace {

bool refactorize(SparseBackend& be, SolverCounters& counters, cholmod_sparse* a, int n, std::string& reason) {
  const auto start = std::chrono::steady_clock::now();
  const auto* ap = static_cast<const int*>(a->p);
  const auto* ai = static_cast<const int*>(a->i);
  const int pos = ap[n];
  const bool same_pattern = be.factor && static_cast<int>(be.pattern_columns.size()) == n + 1 &&
                            std::equal(ap, ap + n + 1, be.pattern_columns.begin()) &&
                            static_cast<int>(be.pattern_rows.size()) == pos &&
                            std::equal(ai, ai + pos, be.pattern_rows.begin());
  be.in_use_updated = false;
  if (!same_pattern) {
    if (be.factor) cholmod_free_factor(&be.factor, &be.common);
    be.factor = cholmod_analyze(a, &be.common);
    be.pattern_columns.assign(ap, ap + n + 1);
    be.pattern_rows.assign(ai, ai + pos);
    be.path_entries.clear();  // noted after the first factorisation (note_ordering)
  }
  counters.symbolic_analyses += !same_pattern;
  ++counters.factorizations;
  bool ok = be.factor != nullptr && cholmod_factorize(a, be.factor, &be.common) != 0;
  if (ok && (be.common.status == CHOLMOD_NOT_POSDEF || be.factor->minor < static_cast<size_t>(n))) {
    ok = false;
    reason = "the system matrix is not positive definite (pivot " + std::to_string(be.factor->minor / 6) +
             " of the free blocks)";
  } else if (!ok) {
    reason = "CHOLMOD factorisation failed (status " + std::to_string(be.common.status) + ")";
  }
  if (!ok) {
    // Force a fresh analysis next time: the failed factor may be in an odd state.
    cholmod_free_factor(&be.factor, &be.common);
    be.pattern_columns.clear();
    be.last_solution.resize(0);
    return false;
  }
  if (be.path_entries.empty()) note_ordering(be);
  be.factor_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

bool preconditioned_cg(SparseBackend& be, const SolverOptions& options, cholmod_sparse* a,
                       const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int& iterations) {
  const auto start = std::chrono::steady_clock::now();
  const int n = static_cast<int>(rhs.size());
  // Iterations are worth it while they cost less than a factorisation; the first
  // attempts, before any iteration has been timed, may use the full allowance.
  int allowed = options.max_iterations;
  if (be.iteration_seconds > 0.0)
    allowed = std::min(allowed, static_cast<int>(be.factor_seconds / be.iteration_seconds));
  if (allowed < 1) return false;

  cholmod_dense* xd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &be.common);
  cholmod_dense* rd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &be.common);
  cholmod_dense* qd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &be.common);
  auto* xp = static_cast<double*>(xd->x);
  auto* rp = static_cast<double*>(rd->x);
  Eigen::Map<Eigen::VectorXd> r(rp, n);
  // r = F - K x
  std::copy(x.data(), x.data() + n, xp);
  std::copy(rhs.data(), rhs.data() + n, rp);
  double minus_one[2] = {-1.0, 0.0}, one[2] = {1.0, 0.0}, zero[2] = {0.0, 0.0};
  cholmod_sdmult(a, 0, minus_one, one, xd, rd, &be.common);
  const double target = options.tolerance * rhs.norm();
  Eigen::VectorXd p, z, q(n);
  double rz = 0.0;
  bool converged = r.norm() <= target;
  iterations = 0;
  while (!converged && iterations < allowed) {
    cholmod_dense* zd = cholmod_solve(CHOLMOD_A, be.factor, rd, &be.common);
    if (zd == nullptr) break;
    z = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(zd->x), n);
    cholmod_free_dense(&zd, &be.common);
    const double rz_new = r.dot(z);
    p = iterations == 0 ? z : Eigen::VectorXd(z + (rz_new / rz) * p);
    rz = rz_new;
    // q = K p
    std::copy(p.data(), p.data() + n, xp);
    cholmod_sdmult(a, 0, one, zero, xd, qd, &be.common);
    q = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(qd->x), n);
    const double pq = p.dot(q);
    ++iterations;
    if (!(pq > 0.0)) break;  // not positive definite along p: let the factorisation decide
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    converged = r.norm() <= target;
  }
  cholmod_free_dense(&xd, &be.common);
  cholmod_free_dense(&rd, &be.common);
  cholmod_free_dense(&qd, &be.common);
  if (iterations > 0) {
    const double per = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / iterations;
    be.iteration_seconds = be.iteration_seconds > 0.0 ? 0.9 * be.iteration_seconds + 0.1 * per : per;
  }
  return converged;
}

}  // namespace

}  // namespace ddafit
