#include "forward/sparse_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include <cholmod.h>
#include <omp.h>

#include "forward/low_rank_change.hpp"

namespace ddafit {

struct SparseSolver::Backend {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  // The system matrix, kept from solve to solve: allocated afresh for every pass it was freed
  // at the top of the heap, which glibc then returned to the system and faulted back in
  // (100,000 page faults on the 411-block wall's 150 steps, a quarter of its run time).
  cholmod_sparse* matrix = nullptr;
  Eigen::VectorXd last_solution;
  double factor_seconds = 0.0;     // wall time of the last factorisation
  double iteration_seconds = 0.0;  // running mean wall time of one CG iteration
  std::vector<int> pattern_columns;
  std::vector<int> pattern_rows;
  // Factor updates (SolverOptions::update_factorization). `updated` is a simplicial LDL'
  // copy of `factor` that the rank-one terms of the passes since it was made have changed;
  // `factored` is the system the factor in use (updated when in_use_updated) stands for.
  cholmod_factor* updated = nullptr;
  bool in_use_updated = false;
  AssembledTerms factored;
  AssembledTerms current;  // the pass's own terms, while it is being solved on an update
  bool factored_valid = false;
  // Of the fill-reducing ordering: the permuted position of each unknown, and for each permuted
  // column the entries of L on its path to the root of the elimination tree (an update's cost).
  std::vector<int> inverse_perm;
  std::vector<double> path_entries;
  double factor_entries_squared = 0.0;  // sum over L's columns of their entry count squared (a factorisation's cost)
};

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

bool refactorize(SparseSolver::Backend& be, SolverCounters& counters, cholmod_sparse* a, int n, std::string& reason);
bool solve_updated(SparseSolver::Backend& be, const SolverOptions& options, SolverCounters& counters,
                   const BlockSparseMatrix& k, cholmod_sparse* a, const Eigen::VectorXd& rhs, Eigen::VectorXd& x);
bool solve_with(cholmod_factor* factor, cholmod_common& common, const Eigen::VectorXd& rhs, Eigen::VectorXd& x);
bool preconditioned_cg(SparseSolver::Backend& be, const SolverOptions& options, cholmod_sparse* a,
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

SparseSolver::SparseSolver(const SolverOptions& options) : options_(options), backend_(std::make_unique<Backend>()) {
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
  Backend& be = *backend_;
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
      static_cast<int>(be.factor->n) == n && solve_updated(be, options_, counters_, k, a, rhs, x)) {
    be.last_solution = x;
    return true;
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

// After a fill-reducing ordering's first factorisation: each unknown's permuted position, and
// for each column of L the entries on its path to the elimination tree's root. A rank-one
// update starting at column j rewrites about path_entries[j] entries of L; a factorisation
// costs about the sum of the squared column counts (Davis & Hager, "Modifying a sparse
// Cholesky factorization", SIAM J. Matrix Anal. Appl. 20, 1999).
void note_ordering(SparseSolver::Backend& be) {
  const cholmod_factor* l = be.factor;
  const int n = static_cast<int>(l->n);
  const auto* perm = static_cast<const int*>(l->Perm);
  be.inverse_perm.assign(n, 0);
  for (int k = 0; k < n; ++k) be.inverse_perm[perm[k]] = k;
  std::vector<int> count(n, 1), parent(n, -1);
  if (l->is_super) {
    const auto* super = static_cast<const int*>(l->super);
    const auto* pi = static_cast<const int*>(l->pi);
    const auto* rows = static_cast<const int*>(l->s);
    for (size_t sn = 0; sn < l->nsuper; ++sn) {
      const int k1 = super[sn], k2 = super[sn + 1];
      const int nrows = pi[sn + 1] - pi[sn];
      for (int j = k1; j < k2; ++j) {
        count[j] = nrows - (j - k1);
        parent[j] = j + 1 < k2 ? j + 1 : (nrows > k2 - k1 ? rows[pi[sn] + (k2 - k1)] : -1);
      }
    }
  } else {
    const auto* lp = static_cast<const int*>(l->p);
    const auto* li = static_cast<const int*>(l->i);
    const auto* lnz = static_cast<const int*>(l->nz);
    for (int j = 0; j < n; ++j) {
      count[j] = lnz[j];
      parent[j] = lnz[j] > 1 ? li[lp[j] + 1] : -1;
    }
  }
  be.path_entries.assign(n, 0.0);
  be.factor_entries_squared = 0.0;
  for (int j = n - 1; j >= 0; --j) {
    be.path_entries[j] = count[j] + (parent[j] > j ? be.path_entries[parent[j]] : 0.0);
    be.factor_entries_squared += static_cast<double>(count[j]) * count[j];
  }
}

bool solve_with(cholmod_factor* factor, cholmod_common& common, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  const int n = static_cast<int>(rhs.size());
  cholmod_dense* b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(b->x));
  cholmod_dense* sol = cholmod_solve(CHOLMOD_A, factor, b, &common);
  cholmod_free_dense(&b, &common);
  if (sol == nullptr) return false;
  x.resize(n);
  std::copy(static_cast<double*>(sol->x), static_cast<double*>(sol->x) + n, x.data());
  cholmod_free_dense(&sol, &common);
  return true;
}

// Applies the rank-one terms to `factor` (an update: LDL' + C C^T; else a downdate), C's rows
// in the factor's permuted order as CHOLMOD requires.
bool apply_terms(SparseSolver::Backend& be, const std::vector<RankOneTerm>& terms, bool update) {
  if (terms.empty()) return true;
  const int n = static_cast<int>(be.inverse_perm.size());
  size_t nnz = 0;
  for (const RankOneTerm& t : terms) nnz += t.rows.size();
  cholmod_sparse* c = cholmod_allocate_sparse(n, terms.size(), nnz, 1, 1, 0, CHOLMOD_REAL, &be.common);
  if (c == nullptr) return false;
  auto* cp = static_cast<int*>(c->p);
  auto* ci = static_cast<int*>(c->i);
  auto* cx = static_cast<double*>(c->x);
  // Each term's entries in permuted rows, and the terms in the order of their first row:
  // CHOLMOD applies them eight at a time, and terms that start near each other in the
  // elimination tree share more of their paths to its root.
  std::vector<std::vector<std::pair<int, double>>> columns(terms.size());
  for (size_t k = 0; k < terms.size(); ++k) {
    for (size_t e = 0; e < terms[k].rows.size(); ++e)
      columns[k].emplace_back(be.inverse_perm[terms[k].rows[e]], terms[k].values[e]);
    std::sort(columns[k].begin(), columns[k].end());
  }
  std::sort(columns.begin(), columns.end(), [](const auto& x, const auto& y) { return x.front().first < y.front().first; });
  int pos = 0;
  for (size_t k = 0; k < columns.size(); ++k) {
    cp[k] = pos;
    for (const auto& [row, value] : columns[k]) ci[pos] = row, cx[pos++] = value;
  }
  cp[terms.size()] = pos;
  const int ok = cholmod_updown(update ? 1 : 0, c, be.updated, &be.common);
  cholmod_free_sparse(&c, &be.common);
  return ok != 0 && be.common.status == CHOLMOD_OK && be.updated->minor == be.updated->n;
}

double relative_residual(cholmod_sparse* a, cholmod_common& common, const Eigen::VectorXd& rhs, const Eigen::VectorXd& x,
                         Eigen::VectorXd& r) {
  const int n = static_cast<int>(rhs.size());
  cholmod_dense* xd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  cholmod_dense* rd = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common);
  std::copy(x.data(), x.data() + n, static_cast<double*>(xd->x));
  std::copy(rhs.data(), rhs.data() + n, static_cast<double*>(rd->x));
  double minus_one[2] = {-1.0, 0.0}, one[2] = {1.0, 0.0};
  cholmod_sdmult(a, 0, minus_one, one, xd, rd, &common);
  r = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(rd->x), n);
  cholmod_free_dense(&xd, &common);
  cholmod_free_dense(&rd, &common);
  const double scale = rhs.norm();
  return scale > 0.0 ? r.norm() / scale : r.norm();
}

// The pass's system K from the factor of the last one, updated by the rank-one terms of the
// change (low_rank_change.hpp), when that costs less than the update_cost_share of a
// factorisation. False: refactorise (`x` is then undefined).
bool solve_updated(SparseSolver::Backend& be, const SolverOptions& options, SolverCounters& counters,
                   const BlockSparseMatrix& k, cholmod_sparse* a, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  if (be.path_entries.empty()) return false;
  const int n = static_cast<int>(rhs.size());
  remember_terms(k, be.current);
  const LowRankChange change = low_rank_change(be.factored, be.current, std::max(8, n / 8));
  if (!change.representable) return false;
  double cost = 0.0;
  for (const auto* terms : {&change.updates, &change.downdates})
    for (const RankOneTerm& t : *terms) {
      int first = n;
      for (const int row : t.rows) first = std::min(first, be.inverse_perm[row]);
      cost += be.path_entries[first];
    }
  if (cost > options.update_cost_share * be.factor_entries_squared) return false;
  if (change.rank() > 0) {
    if (!be.in_use_updated) {
      if (be.updated) cholmod_free_factor(&be.updated, &be.common);
      be.updated = cholmod_copy_factor(be.factor, &be.common);
      if (be.updated == nullptr || !cholmod_change_factor(CHOLMOD_REAL, 0, 0, 0, 1, be.updated, &be.common)) return false;
      be.in_use_updated = true;
    }
    // Updates first: the factor stays positive definite in between.
    if (!apply_terms(be, change.updates, true) || !apply_terms(be, change.downdates, false)) {
      be.in_use_updated = false;
      return false;
    }
  }
  cholmod_factor* factor = be.in_use_updated ? be.updated : be.factor;
  Eigen::VectorXd r, dx;
  bool good = solve_with(factor, be.common, rhs, x) &&
              relative_residual(a, be.common, rhs, x, r) <= options.update_tolerance;
  if (!good && x.allFinite() && solve_with(factor, be.common, r, dx)) {  // one step of refinement
    x += dx;
    good = relative_residual(a, be.common, rhs, x, r) <= options.update_tolerance;
  }
  if (!good || !x.allFinite()) {
    be.in_use_updated = false;
    return false;
  }
  ++counters.factor_updates;
  counters.update_rank += change.rank();
  std::swap(be.factored, be.current);
  return true;
}

bool refactorize(SparseSolver::Backend& be, SolverCounters& counters, cholmod_sparse* a, int n, std::string& reason) {
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

bool preconditioned_cg(SparseSolver::Backend& be, const SolverOptions& options, cholmod_sparse* a,
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
